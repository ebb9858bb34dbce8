#!/usr/bin/python3
"""Checks the built report as a reader sees it: every page of OUT loaded in headless Chromium.

    /usr/bin/python3 reports/site/check_pages.py OUT [--width 1400] [--min-pt 8] [--screens DIR]

For every page OUT/*.html (a complete document; the *_body.html and *_table.html fragments the
builder includes into pages are skipped) at --width CSS px:
  - a full-page screenshot, DIR/<page>.png (default DIR = OUT/screens), --width px wide; a page
    taller than --tile px is saved in tiles <page>-01.png, <page>-02.png, ... (at most
    --max-height px in all), each short enough to be read in an image viewer;
  - every <img> loaded (complete and naturalWidth > 0);
  - no horizontal overflow: the document is no wider than the viewport, else the widest
    elements that stick out are named;
  - no text smaller than --min-pt: HTML text by its computed font-size (pt = px x 0.75); a
    figure by its width on the page and OUT/layout/<png-stem>.json, written by save_figure
    (reports/plotting/common.py): displayed pt = text_min_pt x shown px / (96 x width_in), as
    CSS defines 96 px per inch. An image without a layout file is noted "not measurable";
  - links to other files of the report point at files that exist, and their #anchors at ids
    that exist.
<details> are opened before the text is measured: what a reader can unfold must be readable
too. The screenshot is taken before, as the page first shows.

Chromium is driven over its DevTools protocol on a pipe (--remote-debugging-pipe), with the
standard library only; every wait has a deadline, and a browser that does not answer is killed.
Exit status: 0 every check passed, 1 a check failed (the problems are listed per page),
2 bad input or no Chromium (the Debian package `chromium`).
"""
from __future__ import annotations

import argparse
import base64
import fcntl
import json
import os
import select
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from html.parser import HTMLParser
from pathlib import Path
from urllib.parse import unquote, urlsplit

CSS_PX_PER_IN = 96.0
PT_PER_PX = 0.75  # CSS: 1 px = 1/96 in, 1 pt = 1/72 in
CHROMIUM_NAMES = ("chromium", "chromium-browser")

# Makes lazy images load, then waits (at most ms) until every <img> has loaded or failed.
WAIT_IMAGES_JS = """
async function waitImages(ms) {
  for (const img of document.images) if (img.loading === 'lazy') img.loading = 'eager';
  const pending = [...document.images].filter(img => !img.complete).map(img =>
    new Promise(done => {
      img.addEventListener('load', done);
      img.addEventListener('error', done);
    }));
  await Promise.race([Promise.all(pending), new Promise(done => setTimeout(done, ms))]);
}
"""

PREPARE_JS = WAIT_IMAGES_JS + """
(async () => {
  await waitImages(%(image_ms)d);
  await document.fonts.ready;
  const d = document.documentElement;
  return {height: Math.max(d.scrollHeight, document.body ? document.body.scrollHeight : 0),
          width: d.scrollWidth};
})()
"""

MEASURE_JS = WAIT_IMAGES_JS + """
(async () => {
  for (const d of document.querySelectorAll('details')) d.open = true;
  await waitImages(%(image_ms)d);
  const minPx = %(min_px)f;
  const doc = document.documentElement, body = document.body || doc;
  const vw = doc.clientWidth;

  function describe(el) {
    let s = el.tagName.toLowerCase();
    if (el.id) s += '#' + el.id;
    const cls = [...el.classList].slice(0, 2);
    if (cls.length) s += '.' + cls.join('.');
    if (!el.id) {
      const anc = el.parentElement && el.parentElement.closest('[id]');
      if (anc) s += ' in #' + anc.id;
    }
    return s;
  }
  function contentWidth(el) {
    const cs = getComputedStyle(el), r = el.getBoundingClientRect();
    return r.width - ['paddingLeft', 'paddingRight', 'borderLeftWidth', 'borderRightWidth']
      .reduce((a, k) => a + (parseFloat(cs[k]) || 0), 0);
  }
  function visible(el) {
    return el.checkVisibility({visibilityProperty: true, opacityProperty: true}) &&
           el.getClientRects().length > 0;
  }

  const images = [...document.images].map(img => ({
    src: img.getAttribute('src') || '', url: img.currentSrc || img.src,
    complete: img.complete, natural_width: img.naturalWidth, natural_height: img.naturalHeight,
    shown_px: visible(img) ? contentWidth(img) : 0, where: describe(img)}));

  // Horizontal overflow: the elements that stick out while their parent does not (or the body
  // itself), leaving out what a scrolling or clipping ancestor keeps inside the page.
  const scrollWidth = Math.max(doc.scrollWidth, body.scrollWidth);
  const overflow = [];
  if (scrollWidth > vw) {
    const sticksOut = el => el.getBoundingClientRect().right + window.scrollX > vw + 0.5;
    const clipped = el => {
      for (let a = el.parentElement; a && a !== body && a !== doc; a = a.parentElement)
        if (getComputedStyle(a).overflowX !== 'visible') return true;
      return false;
    };
    for (const el of [body, ...body.querySelectorAll('*')]) {
      if (!sticksOut(el) || clipped(el)) continue;
      const p = el.parentElement;
      if (el !== body && p && p !== doc && sticksOut(p)) continue;
      const r = el.getBoundingClientRect();
      overflow.push({where: describe(el), width: r.width, right: r.right + window.scrollX});
    }
    overflow.sort((a, b) => b.width - a.width);
  }

  // The smallest visible text: the computed font-size of each element holding a text node.
  const small = new Map();
  let textMinPx = null, textMinWhere = '';
  const walker = document.createTreeWalker(body, NodeFilter.SHOW_TEXT);
  const done = new Set();
  for (let n = walker.nextNode(); n; n = walker.nextNode()) {
    const el = n.parentElement;
    if (!el || done.has(el) || !n.data.trim()) continue;
    if (['SCRIPT', 'STYLE', 'NOSCRIPT', 'TEMPLATE', 'TITLE'].includes(el.tagName)) continue;
    done.add(el);
    if (!visible(el)) continue;
    const px = parseFloat(getComputedStyle(el).fontSize);
    if (textMinPx === null || px < textMinPx) { textMinPx = px; textMinWhere = describe(el); }
    if (px < minPx) {
      const key = el.tagName + '.' + [...el.classList].join('.') + ' ' + px;
      const e = small.get(key) || {where: describe(el), px: px, count: 0,
                                   text: n.data.trim().replace(/\\s+/g, ' ').slice(0, 40)};
      e.count += 1;
      small.set(key, e);
    }
  }

  return {
    title: document.title, viewport_width: vw, scroll_width: scrollWidth,
    height: Math.max(doc.scrollHeight, body.scrollHeight),
    images: images, overflow: overflow.slice(0, 8), overflow_count: overflow.length,
    text_min_px: textMinPx, text_min_where: textMinWhere,
    small_text: [...small.values()].sort((a, b) => a.px - b.px),
    links: [...document.querySelectorAll('a[href]')].map(a => a.getAttribute('href')),
  };
})()
"""


class BrowserError(RuntimeError):
    pass


class Browser:
    """One headless Chromium, spoken to over --remote-debugging-pipe: Chromium reads commands
    from fd 3 and writes replies and events to fd 4, each a JSON message ended by a NUL byte."""

    def __init__(self, exe: str, timeout: float):
        self.timeout = timeout
        self.profile = tempfile.mkdtemp(prefix="check_pages.")
        self.log = open(Path(self.profile) / "chromium.log", "w+b")
        # Our pipe ends are moved to fds >= 10 so that the dup2 onto 3 and 4 in the child
        # never lands on one of them; dup2 clears close-on-exec, so only 3 and 4 are inherited.
        cmd_r, self.cmd_w = (self._high(fd) for fd in os.pipe())
        self.res_r, res_w = (self._high(fd) for fd in os.pipe())

        def child_fds():
            os.dup2(cmd_r, 3)
            os.dup2(res_w, 4)

        args = [exe, "--headless", "--remote-debugging-pipe",
                # The sandbox needs user namespaces, which root and most containers lack; we
                # load only the report's own local files.
                "--no-sandbox",
                # Scrollbars would take width from the viewport and from the screenshot.
                "--hide-scrollbars", "--force-device-scale-factor=1",
                "--disable-gpu", "--disable-dev-shm-usage", "--no-first-run",
                "--no-default-browser-check", "--disable-extensions", "--mute-audio",
                "--disable-background-networking", "--user-data-dir=" + self.profile,
                "about:blank"]
        try:
            self.proc = subprocess.Popen(args, stdin=subprocess.DEVNULL,
                                         stdout=subprocess.DEVNULL, stderr=self.log,
                                         close_fds=False, preexec_fn=child_fds,
                                         start_new_session=True)
        finally:
            os.close(cmd_r)
            os.close(res_w)
        self.buf = b""
        self.next_id = 0
        self.events: list[dict] = []
        try:
            self.call("Browser.getVersion", timeout=min(timeout, 30.0))
        except BrowserError:
            self.close()
            raise

    @staticmethod
    def _high(fd: int) -> int:
        high = fcntl.fcntl(fd, fcntl.F_DUPFD_CLOEXEC, 10)
        os.close(fd)
        return high

    def _log_tail(self) -> str:
        self.log.flush()
        self.log.seek(0)
        # The last lines Chromium logged, less its complaints about the absent D-Bus.
        lines = [ln for ln in self.log.read().decode(errors="replace").splitlines()
                 if ln.strip() and "dbus" not in ln]
        return "".join("\n    " + ln for ln in lines[-5:])

    def _read_message(self, deadline: float, waiting_for: str) -> dict:
        while b"\0" not in self.buf:
            left = deadline - time.monotonic()
            ready = select.select([self.res_r], [], [], max(0.0, left))[0] if left > 0 else []
            if not ready:
                raise BrowserError(f"Chromium did not answer in time ({waiting_for})")
            chunk = os.read(self.res_r, 1 << 20)
            if not chunk:
                raise BrowserError("Chromium closed the pipe (exited?)" + self._log_tail())
            self.buf += chunk
        raw, self.buf = self.buf.split(b"\0", 1)
        return json.loads(raw)

    def call(self, method: str, params: dict | None = None, session: str | None = None,
             timeout: float | None = None) -> dict:
        self.next_id += 1
        msg = {"id": self.next_id, "method": method, "params": params or {}}
        if session:
            msg["sessionId"] = session
        try:
            os.write(self.cmd_w, json.dumps(msg).encode() + b"\0")
        except OSError as e:
            raise BrowserError(f"Chromium does not read its pipe: {e}") from e
        deadline = time.monotonic() + (timeout or self.timeout)
        while True:
            reply = self._read_message(deadline, method)
            if reply.get("id") == self.next_id:
                if "error" in reply:
                    raise BrowserError(f"{method}: {reply['error'].get('message')}")
                return reply.get("result", {})
            if "method" in reply:
                self.events.append(reply)

    def wait_event(self, method: str, session: str, timeout: float | None = None) -> dict:
        deadline = time.monotonic() + (timeout or self.timeout)
        while True:
            for i, ev in enumerate(self.events):
                if ev["method"] == method and ev.get("sessionId") == session:
                    return self.events.pop(i)
            self.events.append(self._read_message(deadline, method))

    def evaluate(self, session: str, expression: str, timeout: float | None = None):
        res = self.call("Runtime.evaluate", {"expression": expression, "awaitPromise": True,
                                             "returnByValue": True}, session, timeout)
        if "exceptionDetails" in res:
            ex = res["exceptionDetails"]
            raise BrowserError("page script failed: " +
                               str(ex.get("exception", {}).get("description") or ex.get("text")))
        return res["result"].get("value")

    def close(self) -> None:
        try:
            if self.proc.poll() is None:
                try:
                    os.write(self.cmd_w, json.dumps({"id": 0, "method": "Browser.close"})
                             .encode() + b"\0")
                    self.proc.wait(timeout=3)
                except (OSError, subprocess.TimeoutExpired):
                    pass
            # The browser's helper processes share the session we started it in; none may
            # outlive the check.
            try:
                os.killpg(self.proc.pid, signal.SIGKILL)
            except ProcessLookupError:
                pass
            self.proc.wait(timeout=5)
        except subprocess.TimeoutExpired:
            pass
        finally:
            for fd in (self.cmd_w, self.res_r):
                try:
                    os.close(fd)
                except OSError:
                    pass
            self.log.close()
            shutil.rmtree(self.profile, ignore_errors=True)


def find_chromium(explicit: str | None) -> str | None:
    if explicit:
        return explicit if os.access(explicit, os.X_OK) else None
    if os.environ.get("CHROMIUM"):
        return shutil.which(os.environ["CHROMIUM"])
    for name in CHROMIUM_NAMES:
        found = shutil.which(name)
        if found:
            return found
    return None


def is_page(path: Path) -> bool:
    """A complete HTML document, as opposed to a fragment the builder includes into a page."""
    head = path.read_text(errors="replace")[:2000].lstrip().lower()
    return head.startswith("<!doctype html") or head.startswith("<html")


class Anchors(HTMLParser):
    def __init__(self):
        super().__init__()
        self.ids: set[str] = set()

    def handle_starttag(self, tag, attrs):
        for k, v in attrs:
            if v and (k == "id" or (k == "name" and tag == "a")):
                self.ids.add(v)


_anchor_cache: dict[Path, set[str]] = {}


def anchors_of(path: Path) -> set[str]:
    if path not in _anchor_cache:
        parser = Anchors()
        parser.feed(path.read_text(errors="replace"))
        _anchor_cache[path] = parser.ids
    return _anchor_cache[path]


def check_links(page: Path, hrefs: list[str]) -> list[str]:
    problems = []
    for href in sorted(set(hrefs)):
        parts = urlsplit(href)
        if parts.scheme not in ("", "file") or parts.netloc:
            continue  # another site: not part of the report
        target = (page.parent / unquote(parts.path)).resolve() if parts.path else page.resolve()
        if not target.exists():
            problems.append(f"link to a missing file: {href}")
        elif parts.fragment and target.suffix == ".html" and \
                unquote(parts.fragment) not in anchors_of(target):
            problems.append(f"link to a missing anchor: {href} (no id {parts.fragment!r} in "
                            f"{target.name})")
    return problems


def local_file(page: Path, url: str) -> Path | None:
    parts = urlsplit(url)
    if parts.scheme != "file" and not (parts.scheme == "" and parts.path):
        return None
    path = Path(unquote(parts.path))
    return path if path.is_absolute() else (page.parent / path).resolve()


def check_figures(out: Path, page: Path, images: list[dict], min_pt: float
                  ) -> tuple[list[str], list[str], list[float]]:
    problems, notes, shown_pts = [], [], []
    for img in images:
        if not img["complete"] or img["natural_width"] <= 0:
            path = local_file(page, img["url"])
            why = " (no such file)" if path is not None and not path.exists() else ""
            problems.append(f"broken image: {img['src']!r}{why} at {img['where']}")
            continue
        path = local_file(page, img["url"])
        layout_path = out / "layout" / f"{path.stem}.json" if path else None
        if layout_path is None or not layout_path.exists():
            notes.append(f"{img['src']}: not measurable (no layout/"
                         f"{path.stem if path else '?'}.json)")
            continue
        lay = json.loads(layout_path.read_text())
        if lay.get("text_min_pt") is None:
            continue  # a figure without text
        if img["shown_px"] <= 0:
            notes.append(f"{img['src']}: not shown on the page, text not measured")
            continue
        scale = img["shown_px"] / (CSS_PX_PER_IN * lay["width_in"])
        pt = lay["text_min_pt"] * scale
        shown_pts.append(pt)
        if pt < min_pt:
            smallest = [s for s in lay.get("smallest", []) if s["pt"] * scale < min_pt]
            seen, texts = set(), []
            for s in smallest:
                if (s["pt"], s["text"]) not in seen:
                    seen.add((s["pt"], s["text"]))
                    texts.append(f"{s['text']!r} {s['pt']:g} pt -> {s['pt'] * scale:.1f}")
            problems.append(
                f"figure text too small: {img['src']} shown {img['shown_px']:.0f} px wide, "
                f"{lay['width_in']:g} in figure: smallest text {pt:.1f} pt < {min_pt:g} "
                f"({', '.join(texts[:4])})")
    return problems, notes, shown_pts


def screenshot(browser: Browser, session: str, width: int, height: int, dest: Path,
               tile: int, max_height: int) -> list[Path]:
    """The page from its top, --width px wide, in tiles of at most `tile` px."""
    height = max(1, min(height, max_height))
    tiles = [(y, min(tile, height - y)) for y in range(0, height, tile)]
    stem = dest.stem
    for old in dest.parent.glob(f"{stem}*.png"):
        if old.stem == stem or old.stem[len(stem) + 1:].isdigit():
            old.unlink()
    paths = []
    for i, (y, h) in enumerate(tiles, 1):
        path = dest if len(tiles) == 1 else dest.with_name(f"{stem}-{i:02d}.png")
        shot = browser.call("Page.captureScreenshot", {
            "format": "png", "captureBeyondViewport": True, "fromSurface": True,
            "clip": {"x": 0, "y": y, "width": width, "height": h, "scale": 1}}, session)
        path.write_bytes(base64.b64decode(shot["data"]))
        paths.append(path)
    return paths


def check_page(browser: Browser, out: Path, page: Path, args) -> dict:
    result: dict = {"page": page.name, "problems": [], "notes": [], "screens": []}
    target = browser.call("Target.createTarget", {"url": "about:blank"})["targetId"]
    try:
        session = browser.call("Target.attachToTarget",
                               {"targetId": target, "flatten": True})["sessionId"]
        browser.call("Page.enable", session=session)
        browser.call("Emulation.setDeviceMetricsOverride",
                     {"width": args.width, "height": args.viewport_height,
                      "deviceScaleFactor": 1, "mobile": False}, session)
        nav = browser.call("Page.navigate", {"url": page.resolve().as_uri()}, session)
        if nav.get("errorText"):
            raise BrowserError(f"could not load the page: {nav['errorText']}")
        browser.wait_event("Page.loadEventFired", session, args.timeout)
        image_ms = int(args.timeout * 1000 / 3)
        size = browser.evaluate(session, PREPARE_JS % {"image_ms": image_ms})
        dest = args.screens / f"{page.stem}.png"
        result["screens"] = [str(p) for p in screenshot(
            browser, session, args.width, int(size["height"]), dest, args.tile, args.max_height)]
        if size["height"] > args.max_height:
            result["notes"].append(f"screenshot cut at {args.max_height} px of "
                                   f"{size['height']} px")
        m = browser.evaluate(session, MEASURE_JS % {"image_ms": image_ms,
                                                    "min_px": args.min_pt / PT_PER_PX})
    finally:
        try:
            browser.call("Target.closeTarget", {"targetId": target})
        except BrowserError:
            pass

    problems, notes = result["problems"], result["notes"]
    result.update(height=m["height"], scroll_width=m["scroll_width"],
                  viewport_width=m["viewport_width"], images=len(m["images"]),
                  links=len(m["links"]))
    # (a), (c) figures: broken images and the figures' smallest text as shown.
    fig_problems, fig_notes, shown_pts = check_figures(out, page, m["images"], args.min_pt)
    result["broken_images"] = sum(p.startswith("broken image") for p in fig_problems)
    result["small_figures"] = sum(p.startswith("figure text") for p in fig_problems)
    result["figure_min_pt"] = min(shown_pts) if shown_pts else None
    result["not_measurable"] = sum("not measurable" in n for n in fig_notes)
    problems += [p for p in fig_problems if p.startswith("broken image")]
    # (b) horizontal overflow.
    if m["scroll_width"] > m["viewport_width"]:
        when = " once its <details> are open" if size["width"] <= m["viewport_width"] else ""
        culprits = "; ".join(f"{o['where']} {o['width']:.0f} px wide, right edge at "
                             f"{o['right']:.0f}" for o in m["overflow"][:4])
        more = m["overflow_count"] - min(4, len(m["overflow"]))
        problems.append(f"page is {m['scroll_width']} px wide in a {m['viewport_width']} px "
                        f"viewport{when}: {culprits or 'no single element found'}"
                        + (f" (+{more} more)" if more > 0 else ""))
    # (c) HTML text.
    result["text_min_pt"] = m["text_min_px"] * PT_PER_PX if m["text_min_px"] else None
    for s in m["small_text"][:10]:
        problems.append(f"HTML text too small: {s['px'] * PT_PER_PX:.1f} pt ({s['px']:g} px) "
                        f"in {s['where']}" + (f" and {s['count'] - 1} more like it"
                                              if s["count"] > 1 else "")
                        + f": {s['text']!r}")
    if len(m["small_text"]) > 10:
        problems.append(f"HTML text too small: {len(m['small_text']) - 10} more kinds of "
                        "element")
    problems += [p for p in fig_problems if not p.startswith("broken image")]
    notes += fig_notes
    # (d) links between the report's files.
    link_problems = check_links(page, m["links"])
    result["broken_links"] = len(link_problems)
    problems += link_problems
    return result


def summary_line(r: dict, min_pt: float) -> str:
    if "error" in r:
        return f"{r['page']}: FAIL — {r['error']}"
    fig = (f"figures' smallest text {r['figure_min_pt']:.1f} pt, {r['small_figures']} below "
           f"{min_pt:g}" if r["figure_min_pt"] is not None else "no measurable figure")
    html_pt = f"{r['text_min_pt']:.1f} pt" if r["text_min_pt"] else "none"
    return (f"{r['page']}: {'FAIL' if r['problems'] else 'ok'} — {r['height']} px tall, "
            f"{r['scroll_width']}/{r['viewport_width']} px wide; {r['images']} images, "
            f"{r['broken_images']} broken; HTML text ≥ {html_pt}; {fig}"
            + (f", {r['not_measurable']} not measurable" if r["not_measurable"] else "")
            + f"; {r['links']} links, {r['broken_links']} broken")


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("out", type=Path, help="the built report (its *.html pages)")
    ap.add_argument("--width", type=int, default=1400, help="viewport width, CSS px")
    ap.add_argument("--min-pt", type=float, default=8.0, help="smallest readable text, pt")
    ap.add_argument("--screens", type=Path, help="screenshot folder (default OUT/screens)")
    ap.add_argument("--tile", type=int, default=2000, help="screenshot tile height, px")
    ap.add_argument("--max-height", type=int, default=120000,
                    help="screenshot height cap, px")
    ap.add_argument("--viewport-height", type=int, default=900, help=argparse.SUPPRESS)
    ap.add_argument("--timeout", type=float, default=60.0,
                    help="seconds one page may take (each wait of the browser)")
    ap.add_argument("--chromium", help="the browser (default: chromium on PATH, or $CHROMIUM)")
    ap.add_argument("--json", type=Path, help="also write the results here as JSON")
    args = ap.parse_args(argv)

    out = args.out
    if not out.is_dir():
        print(f"check_pages.py: {out} is not a folder", file=sys.stderr)
        return 2
    pages = [p for p in sorted(out.glob("*.html")) if is_page(p)]
    if not pages:
        print(f"check_pages.py: no HTML page in {out}", file=sys.stderr)
        return 2
    exe = find_chromium(args.chromium)
    if exe is None:
        print("check_pages.py: Chromium not found"
              + (f" at {args.chromium}" if args.chromium else
                 f" (looked for {', '.join(CHROMIUM_NAMES)} on PATH)")
              + "; install the Debian package `chromium` (`make deps-test` does)", file=sys.stderr)
        return 2
    args.screens = args.screens or out / "screens"
    args.screens.mkdir(parents=True, exist_ok=True)

    try:
        browser = Browser(exe, args.timeout)
    except (BrowserError, OSError) as e:
        print(f"check_pages.py: could not start Chromium ({exe}): {e}", file=sys.stderr)
        return 2
    results = []
    try:
        for page in pages:
            try:
                if browser is None:
                    browser = Browser(exe, args.timeout)
                results.append(check_page(browser, out, page, args))
            except (BrowserError, OSError, KeyError, TypeError, ValueError) as e:
                results.append({"page": page.name, "error": str(e),
                                "problems": [f"not checked: {e}"], "notes": []})
                if browser is not None:  # a fresh browser for the next page
                    browser.close()
                    browser = None
    finally:
        if browser is not None:
            browser.close()

    for r in results:
        print(summary_line(r, args.min_pt))
    for r in results:
        if r["problems"] or r["notes"]:
            print(f"\n{r['page']}: {len(r['problems'])} problem(s)")
            for p in r["problems"]:
                print(f"  - {p}")
            for n in r["notes"]:
                print(f"  note: {n}")
    failed = [r["page"] for r in results if r["problems"]]
    print(f"\ncheck_pages: {len(results)} page(s), screenshots in {args.screens}; "
          + (f"FAILED: {', '.join(failed)}" if failed else "all checks passed"))
    if args.json:
        args.json.write_text(json.dumps(results, indent=1) + "\n")
    return 1 if failed else 0


if __name__ == "__main__":
    raise SystemExit(main())
