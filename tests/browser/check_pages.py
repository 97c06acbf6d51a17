#!/usr/bin/env python3
"""Opens aoreplay's HTML reports in headless Chromium (Debian's `chromium`) and fails on any
console error, uncaught exception or failed load, or when a page misses its key elements; saves a
full-page screenshot of each.

    check_pages.py --screenshots DIR KIND=PAGE.html ...   (KIND: run, sweep, compare)

Talks the DevTools protocol over --remote-debugging-pipe (JSON messages ended by NUL on fds 3/4),
so it needs nothing beyond Python's standard library. Network access is blocked: a page that
needs it fails.
"""
import argparse
import base64
import fcntl
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time

# Per kind: a JavaScript expression returning a list of problems (empty when the page is whole).
KEY_ELEMENTS = {
    "run": r"""
      (() => {
        const problems = [];
        const need = (selector, what) => { if (!document.querySelector(selector)) problems.push('missing ' + what + ' (' + selector + ')'); };
        need('#overview dl.facts', 'run facts');
        need('#pass-times svg rect', 'per-pass bars');
        need('#frame-times svg polyline, #frame-times svg circle', 'per-frame GPU time');
        need('#images img', 'frame images');
        need('#images .colour-scale', 'colour scale');
        need('#metrics-over-time svg', 'metrics over time');
        need('#passes table#passes-run tbody tr', 'passes run');
        need('#graph svg, #graph pre', 'render graph');
        need('#memory table#memory-table tbody tr', 'memory per resource');
        document.querySelectorAll('img').forEach((img, i) => {
          if (!img.complete || img.naturalWidth === 0) problems.push('image ' + i + ' did not decode');
        });
        return problems;
      })()""",
    "sweep": r"""
      (() => {
        const problems = [];
        if (!document.querySelector('#pareto svg circle')) problems.push('missing error-vs-ms plot points');
        const table = document.querySelector('table#configurations.sortable');
        if (!table || table.tBodies[0].rows.length === 0) { problems.push('missing configurations table'); return problems; }
        // Sorting works: a click on "total ms" orders the rows by it.
        const headings = Array.from(table.tHead.rows[0].cells);
        const column = headings.findIndex(th => th.textContent === 'total ms');
        if (column < 0) { problems.push('no total ms column'); return problems; }
        headings[column].click();
        const values = Array.from(table.tBodies[0].rows).map(r => parseFloat(r.cells[column].dataset.value));
        for (let i = 1; i < values.length; ++i) if (values[i] < values[i - 1]) problems.push('sorting by total ms failed');
        return problems;
      })()""",
    "compare": r"""
      (() => {
        const problems = [];
        if (!document.querySelector('table#verdicts tbody tr td.verdict')) problems.push('missing verdicts');
        if (!document.querySelector('#distributions svg.strip circle')) problems.push('missing distributions');
        return problems;
      })()""",
}


def high_fd(fd):
    """The fd moved to 10 or above, clear of the 3 and 4 the child needs."""
    moved = fcntl.fcntl(fd, fcntl.F_DUPFD, 10)
    os.close(fd)
    return moved


class Browser:
    def __init__(self, chromium):
        self.profile = tempfile.mkdtemp(prefix="aoreplay-chromium-")
        to_child_r, self.to_child = (high_fd(fd) for fd in os.pipe())
        self.from_child, from_child_w = (high_fd(fd) for fd in os.pipe())

        args = ["--headless", "--no-sandbox", "--disable-gpu", "--remote-debugging-pipe",
                "--no-first-run", "--no-default-browser-check", "--disable-extensions",
                f"--user-data-dir={self.profile}", "about:blank"]
        # The protocol runs on fds 3 (commands in) and 4 (replies out): a shell puts the pipes there.
        wire = f'exec "$0" "$@" 3<&{to_child_r} 4>&{from_child_w} {to_child_r}<&- {from_child_w}>&-'
        self.process = subprocess.Popen(["bash", "-c", wire, chromium] + args, pass_fds=(to_child_r, from_child_w),
                                        stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        os.close(to_child_r)
        os.close(from_child_w)
        self.buffer = b""
        self.next_id = 0
        self.events = []

    def _read_message(self, deadline):
        while b"\0" not in self.buffer:
            if time.monotonic() > deadline:
                raise TimeoutError("chromium did not answer")
            chunk = os.read(self.from_child, 1 << 16)
            if not chunk:
                raise RuntimeError("chromium closed the pipe")
            self.buffer += chunk
        message, self.buffer = self.buffer.split(b"\0", 1)
        return json.loads(message)

    def send(self, method, params=None, session=None, timeout=60):
        self.next_id += 1
        message = {"id": self.next_id, "method": method, "params": params or {}}
        if session:
            message["sessionId"] = session
        os.write(self.to_child, json.dumps(message).encode() + b"\0")
        deadline = time.monotonic() + timeout
        while True:
            reply = self._read_message(deadline)
            if reply.get("id") == self.next_id:
                if "error" in reply:
                    raise RuntimeError(f"{method}: {reply['error']}")
                return reply.get("result", {})
            self.events.append(reply)

    def wait_for(self, method, timeout=60):
        deadline = time.monotonic() + timeout
        for i, event in enumerate(self.events):
            if event.get("method") == method:
                return self.events.pop(i)
        while True:
            event = self._read_message(deadline)
            if event.get("method") == method:
                return event
            self.events.append(event)

    def close(self):
        try:
            self.send("Browser.close", timeout=10)
        except Exception:
            pass
        try:
            self.process.wait(timeout=10)
        except subprocess.TimeoutExpired:
            self.process.kill()
        shutil.rmtree(self.profile, ignore_errors=True)


def problems_of_events(events):
    problems = []
    for e in events:
        method, params = e.get("method"), e.get("params", {})
        if method == "Runtime.exceptionThrown":
            details = params.get("exceptionDetails", {})
            problems.append("uncaught exception: " + details.get("exception", {}).get("description", details.get("text", "?")))
        elif method == "Runtime.consoleAPICalled" and params.get("type") in ("error", "assert"):
            problems.append("console." + params["type"] + ": " + " ".join(str(a.get("value", a.get("description", ""))) for a in params.get("args", [])))
        elif method == "Log.entryAdded" and params.get("entry", {}).get("level") == "error":
            entry = params["entry"]
            problems.append(f"log error ({entry.get('source')}): {entry.get('text')} {entry.get('url', '')}".strip())
    return problems


def check_page(browser, kind, page, screenshot):
    target = browser.send("Target.createTarget", {"url": "about:blank"})["targetId"]
    session = browser.send("Target.attachToTarget", {"targetId": target, "flatten": True})["sessionId"]
    for method in ("Runtime.enable", "Log.enable", "Page.enable", "Network.enable"):
        browser.send(method, session=session)
    browser.send("Network.setBlockedURLs", {"urls": ["http://*", "https://*", "ws://*", "wss://*"]}, session=session)
    browser.send("Emulation.setDeviceMetricsOverride", {"width": 1280, "height": 900, "deviceScaleFactor": 1, "mobile": False},
                 session=session)
    browser.events.clear()
    browser.send("Page.navigate", {"url": "file://" + os.path.abspath(page)}, session=session)
    browser.wait_for("Page.loadEventFired")
    result = browser.send("Runtime.evaluate", {"expression": KEY_ELEMENTS[kind], "returnByValue": True}, session=session)
    problems = []
    if "exceptionDetails" in result:
        problems.append("the key-element check threw: " + json.dumps(result["exceptionDetails"])[:300])
    else:
        problems += result["result"].get("value", ["the key-element check returned nothing"])
    time.sleep(0.2)  # late console messages
    browser.send("Runtime.evaluate", {"expression": "0"}, session=session)  # flushes queued events
    problems += problems_of_events([e for e in browser.events if e.get("sessionId") == session])
    metrics = browser.send("Page.getLayoutMetrics", session=session)
    height = min(int(metrics.get("cssContentSize", metrics.get("contentSize"))["height"]), 6000)
    shot = browser.send("Page.captureScreenshot", {"format": "png", "captureBeyondViewport": True,
                                                   "clip": {"x": 0, "y": 0, "width": 1280, "height": height, "scale": 1}},
                        session=session)
    with open(screenshot, "wb") as f:
        f.write(base64.b64decode(shot["data"]))
    browser.send("Target.closeTarget", {"targetId": target})
    browser.events.clear()
    return problems


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--screenshots", required=True, help="folder for KIND.png")
    parser.add_argument("--chromium", default=shutil.which("chromium") or "chromium")
    parser.add_argument("pages", nargs="+", help="KIND=PAGE.html")
    args = parser.parse_args()
    if not shutil.which(args.chromium):
        print(f"check_pages: {args.chromium} not found (Debian package chromium; .ci/install-deps.sh installs it)")
        return 2
    os.makedirs(args.screenshots, exist_ok=True)
    browser = Browser(args.chromium)
    failed = False
    try:
        for item in args.pages:
            kind, page = item.split("=", 1)
            shot = os.path.join(args.screenshots, f"{kind}.png")
            problems = check_page(browser, kind, page, shot)
            for p in problems:
                print(f"check_pages: {page}: {p}")
            print(f"check_pages: {kind} {page}: {'FAILED' if problems else 'ok'}; screenshot {shot}")
            failed |= bool(problems)
    finally:
        browser.close()
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
