#!/usr/bin/env python3
"""Frames per second of spinning pages (`cargo xtask bake ... --html PAGE` or `--canvas
PAGE`) playing live in headless Chromium with software compositing, one after another.

For a CSS page, a "still" variant is measured beside it: every element and the shared
`rotate` animation, without the opacity keyframes that switch copies of pieces between cells,
so the two differ only in the switches. A canvas page (the canvas player) is measured as it
is. A script added to each page counts `requestAnimationFrame` callbacks over `--seconds`
(after a 1.5 s warm-up) and posts the figures to a local server.

    python3 xtask/scripts/live_fps.py PAGE [PAGE ...] [--seconds 8] [--browser chromium] [--no-still]
"""

import argparse
import http.server
import json
import os
import re
import shutil
import signal
import subprocess
import tempfile
import threading
import time

PROBE = """<script>
(function(){
 let t0 = null, last = null, gaps = [];
 function tick(t){
   if (SWEEP) {
     // A pointer sweeping the page: across once every 4 s, up and down once every 3 s.
     const x = innerWidth * (0.5 + 0.45 * Math.sin(t / 4000 * 2 * Math.PI));
     const y = innerHeight * (0.5 + 0.45 * Math.sin(t / 3000 * 2 * Math.PI));
     dispatchEvent(new PointerEvent('pointermove', {clientX: x, clientY: y, bubbles: true}));
   }
   if (t0 === null) { t0 = t; last = t; }
   else { gaps.push(t - last); last = t; }
   if (t - t0 < SECONDS * 1000) { requestAnimationFrame(tick); return; }
   gaps.sort((a, b) => a - b);
   const q = p => gaps[Math.min(gaps.length - 1, Math.floor(p * gaps.length))];
   fetch('/NAME', {method: 'POST', body: JSON.stringify({
     frames: gaps.length, seconds: (last - t0) / 1000,
     fps: gaps.length / ((last - t0) / 1000),
     median_ms: q(0.5), p95_ms: q(0.95), max_ms: gaps[gaps.length - 1]})});
 }
 setTimeout(() => requestAnimationFrame(tick), 1500);
})();
</script>"""


def still(page: str) -> str:
    """The page without the copies' opacity switches (each keeps only the rotation)."""
    return re.sub(r"(\.v\d+\{animation:t [^,}]*),v\d+ [^}]*\}", r"\1}", page)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("pages", nargs="+")
    parser.add_argument("--no-still", action="store_true", help="skip the CSS pages' still variant")
    parser.add_argument("--sweep", action="store_true", help="move a pointer across the page every frame")
    parser.add_argument("--seconds", type=float, default=8.0)
    parser.add_argument("--browser", default="chromium")
    args = parser.parse_args()
    work = tempfile.mkdtemp(prefix="live-fps-")
    results: dict[str, dict] = {}

    class Handler(http.server.SimpleHTTPRequestHandler):
        def __init__(self, *a, **k):
            super().__init__(*a, directory=work, **k)

        def do_POST(self):
            body = self.rfile.read(int(self.headers["Content-Length"]))
            results[self.path.strip("/")] = json.loads(body)
            self.send_response(200)
            self.end_headers()

        def log_message(self, *a):
            pass

    server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), Handler)
    threading.Thread(target=server.serve_forever, daemon=True).start()
    variants = []
    for path in args.pages:
        page = open(path, encoding="utf-8").read()
        stem = os.path.splitext(os.path.basename(path))[0]
        if "<canvas" in page or args.sweep:
            variants.append((stem, page))
        else:
            variants.append((f"{stem}-switching", page))
            if not args.no_still:
                variants.append((f"{stem}-still", still(page)))
    for name, html in variants:
        probe = (PROBE.replace("SECONDS", str(args.seconds)).replace("NAME", name)
                 .replace("SWEEP", "true" if args.sweep else "false"))
        html = html.replace("</body>", probe + "</body>") if "</body>" in html else html + probe
        with open(os.path.join(work, name + ".html"), "w", encoding="utf-8") as f:
            f.write(html)
        browser = subprocess.Popen(
            [args.browser, "--headless", "--no-sandbox", "--disable-gpu", "--hide-scrollbars",
             "--window-size=512,512", f"--user-data-dir={work}/profile-{name}",
             "--remote-debugging-port=0",
             f"http://127.0.0.1:{server.server_port}/{name}.html"],
            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True)
        deadline = time.time() + 120 + args.seconds
        while name not in results and time.time() < deadline:
            time.sleep(0.5)
        # The whole process group: the renderer would go on animating otherwise.
        os.killpg(browser.pid, signal.SIGKILL)
        browser.wait()
        time.sleep(2)
        r = results.get(name)
        if r is None:
            print(f"{name}: no result within {120 + args.seconds:.0f} s")
            continue
        print(f"{name}: {r['fps']:.2f} frames/s over {r['seconds']:.1f} s "
              f"(median {r['median_ms']:.0f} ms, 95th percentile {r['p95_ms']:.0f} ms, "
              f"longest {r['max_ms']:.0f} ms)")
    server.shutdown()
    shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
