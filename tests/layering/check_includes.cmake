# The floors of the project include downwards only (DESIGN.md: Layout):
#   lib/            the physics; never includes sweeps/
#   sweeps/engine/  the sweep engine; never includes sweeps/points/ or sweeps/cli/
#   sweeps/points/  the point families; never includes sweeps/cli/
# Run as `cmake -DSOURCE_DIR=<repo> -P check_includes.cmake`; fails listing every offending line.
if(NOT SOURCE_DIR)
  message(FATAL_ERROR "check_includes.cmake: pass -DSOURCE_DIR=<repository root>")
endif()

set(violations "")
set(checked 0)

# floor: folder under SOURCE_DIR; forbidden: regex of include paths it may not name.
function(check_floor floor forbidden)
  file(GLOB_RECURSE sources "${SOURCE_DIR}/${floor}/*.hpp" "${SOURCE_DIR}/${floor}/*.cpp"
       "${SOURCE_DIR}/${floor}/*.h" "${SOURCE_DIR}/${floor}/*.cc")
  list(LENGTH sources n)
  math(EXPR total "${checked} + ${n}")
  set(checked ${total} PARENT_SCOPE)
  foreach(src IN LISTS sources)
    file(STRINGS "${src}" lines REGEX "^[ \t]*#[ \t]*include[ \t]*[\"<](${forbidden})")
    foreach(line IN LISTS lines)
      file(RELATIVE_PATH rel "${SOURCE_DIR}" "${src}")
      string(STRIP "${line}" line)
      list(APPEND violations "${rel}: ${line}")
    endforeach()
  endforeach()
  set(violations "${violations}" PARENT_SCOPE)
endfunction()

check_floor(lib "sweeps/|cli/")
check_floor(sweeps/engine "sweeps/points/|sweeps/cli/")
check_floor(sweeps/points "sweeps/cli/")

if(checked EQUAL 0)
  message(FATAL_ERROR "check_includes.cmake: no sources found under ${SOURCE_DIR}")
endif()
list(LENGTH violations n_bad)
if(n_bad GREATER 0)
  list(JOIN violations "\n  " text)
  message(FATAL_ERROR "an include points upward (${n_bad}):\n  ${text}")
endif()
message(STATUS "layering: ${checked} sources, every include points downward")
