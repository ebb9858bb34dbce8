#pragma once
// The planner's inner loop in one routine (thesis §5.5: every option is T_s evaluations of the
// ch. 3 model): the spring support (§3.3) and the viscous-Coulomb balance (§3.4) of one option at
// one substep, fused and warm-started, with the reference kernels as the fallback wherever this
// route cannot certify its answer. option_kernel.cpp dispatches to it; the reference loop stays
// (integrate_option_reference) for the tests.
//
// Why it is faster and still the same model:
//  - Substep 0 is the node's configuration for every option (q does not depend on the speeds):
//    its spring support is solved once per node (NodeTable::start_*), by the reference itself.
//  - Successive substeps move the feet by a few millimetres, so the previous substep's contact set
//    and state (α, β, z) are one Newton step from the new balance: the active-set Newton of
//    contact/support_newton.cpp started there instead of at the all-feet plane. Its certificate is
//    the reference's (contact set read off the heights repeats, no foot within 10³ × rounding of
//    its plane, the cell's Hessian safely definite, balance residual at rounding): U is then
//    strictly convex around the state and the state is its unique minimizer, which is also what
//    contact::spring_support returns. Anything else falls back to contact::spring_support.
//  - The pass that certifies the support also sums the viscous balance (c_k = μ_k F_z,k, eq.
//    3.19 with G = I) and its 3 × 3 system is solved by cofactors (one division) when its pivots
//    pass friction's definiteness test; a robot with anisotropy (w ≠ 0), a Coulomb law, or a
//    singular balance take the reference solvers.
//  - The SE(2) advance (core::advance) carries cos θ, sin θ along the substeps (one rotation
//    product per substep) and evaluates sin, cos and sinc of the small half angle ω h / 2 by their
//    Taylor series (the omitted term below 1e-20 relative for |ω h / 2| < 0.05).
//  - kBatch options run side by side, one per lane of GCC vector types (an AVX2 clone without FMA
//    and the portable SSE2 default, the same operations and rounding): up to two warm Newton
//    steps, the balance and the advance per lane. A lane that does not certify there takes the
//    scalar route (the same steps one option at a time, then the reference) for that substep.
// The result differs from the reference only by rounding (tests/planning/test_option_kernel.cpp:
// 1e-12 relative on end poses). Every lane computes with its own numbers only and the route it
// takes depends on them only, so an option's result does not depend on the other options of its
// batch or chunk, nor on the thread that runs it (the same bits alone or beside others).
//
// Cost (bench_planning, BigANT, one thread): about 25 ns per option-substep against 250 ns for the
// reference loop; a full step of 4096 options × 20 substeps takes about 2 ms.
#include "contact/robot.hpp"
#include "core/se2.hpp"

namespace slipwalk::planning {

struct NodeTable;
struct PlanRobot;
struct PlanOptions;

namespace detail {

/// Which route each substep took (for the tests; counted only when asked for).
struct FastCounts {
  long long substeps = 0;  ///< substeps integrated
  long long scalar = 0;  ///< substeps a batch lane took by the scalar route (not certified at once)
  long long support_fallbacks = 0;   ///< substeps whose support contact::spring_support decided
  long long friction_fallbacks = 0;  ///< substeps friction::solve_viscous_coulomb solved
  long long reference = 0;           ///< options handed whole to the reference (anisotropic robot)
};

/// Options integrated side by side (one per lane of the batch's vectors).
inline constexpr int kBatch = 4;

/// The fast route for options.law = kViscousCoulomb: integrate_option for `count` ≤ kBatch
/// options at once (columns[l]: option l's N speed columns; poses[l] advanced; ok[l] its
/// feasibility). An option's result does not depend on `count` nor on the other options.
void integrate_batch(const PlanRobot& robot, const PlanOptions& options, const NodeTable& table,
                     const int* const* columns, int count, int substeps, core::Pose2* poses,
                     bool* ok, contact::Frame& frame, FastCounts* counts = nullptr);

/// The same option by option, scalar (a second implementation for the tests, and the route a
/// lane takes for a substep the batch cannot certify at once).
bool integrate_option_scalar(const PlanRobot& robot, const PlanOptions& options,
                             const NodeTable& table, const int* columns, int substeps,
                             core::Pose2& pose, contact::Frame& frame,
                             FastCounts* counts = nullptr);

/// Not for callers: the batch's vector code (an AVX2 clone and the portable default).
void integrate_batch_vector(const PlanRobot& robot, const NodeTable& table,
                            const int* const* columns, int count, int substeps, core::Pose2* poses,
                            bool* ok, contact::Frame& frame, FastCounts* counts);

/// Fills the table's substep-0 support (NodeTable::start_*) from `frame`, on which
/// contact::spring_support has just run at the node's configuration.
void store_start_support(const PlanRobot& robot, const contact::Frame& frame, NodeTable& table);

}  // namespace detail
}  // namespace slipwalk::planning
