"""A headless Chromium driven through the DevTools protocol over a pipe (``--remote-debugging-pipe``:
JSON messages ending in NUL on file descriptors 3 and 4), to check pages as a reader sees them:
every image loads, every link leads to a file that exists, every #anchor to an element.

No dependency beyond the standard library and the browser (Debian's ``chromium``); no network
(file:// pages only; the flags keep Chromium from trying to reach any server). Loaded by the
tests with importlib (tests/test_browser.py).
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import tempfile
import time
from pathlib import Path
from urllib.parse import unquote, urldefrag, urlparse

FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
         "--disable-background-networking", "--disable-component-update", "--disable-sync",
         "--disable-default-apps", "--disable-extensions", "--mute-audio", "--remote-debugging-pipe"]

#: what a page reports about itself once loaded
_INSPECT = """JSON.stringify({
  images: Array.from(document.images).map(i => ({src: i.currentSrc || i.src, ok: i.complete && i.naturalWidth > 0})),
  links: Array.from(document.querySelectorAll('a[href]')).map(a => a.href),
  ids: Array.from(document.querySelectorAll('[id]')).map(e => e.id)
     .concat(Array.from(document.querySelectorAll('a[name]')).map(e => e.name)),
  title: document.title,
  text: document.body ? document.body.innerText.length : 0
})"""


def chromium() -> str | None:
    """The browser's path (Debian: chromium; elsewhere chromium-browser or google-chrome)."""
    for name in ("chromium", "chromium-browser", "google-chrome"):
        path = shutil.which(name)
        if path:
            return path
    return None


class Browser:
    """One headless Chromium; :meth:`inspect` loads a file:// URL in a tab and returns what
    :data:`_INSPECT` collects, plus the resources that failed to load."""

    def __init__(self, exe: str, timeout: float = 60.0):
        self.timeout = timeout
        self._profile = tempfile.TemporaryDirectory(prefix="chromium-profile-")
        to_browser_r, self._to_browser = os.pipe()
        self._from_browser, from_browser_w = os.pipe()

        def fds():  # the child reads commands on fd 3 and writes replies on fd 4 (kept: pass_fds)
            hi_r, hi_w = os.dup(to_browser_r), os.dup(from_browser_w)
            os.dup2(hi_r, 3)
            os.dup2(hi_w, 4)

        self._proc = subprocess.Popen([exe, *FLAGS, f"--user-data-dir={self._profile.name}", "about:blank"],
                                      stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                                      stderr=subprocess.DEVNULL, preexec_fn=fds, pass_fds=(3, 4))
        os.close(to_browser_r)
        os.close(from_browser_w)
        self._buffer = b""
        self._id = 0
        self._events: list[dict] = []

    def close(self):
        try:
            self._send("Browser.close")
        except (OSError, TimeoutError, RuntimeError):
            pass
        try:
            self._proc.wait(timeout=10)
        except subprocess.TimeoutExpired:
            self._proc.kill()
            self._proc.wait()
        for fd in (self._to_browser, self._from_browser):
            try:
                os.close(fd)
            except OSError:
                pass
        self._profile.cleanup()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    # -- the protocol --------------------------------------------------------------------
    def _read_message(self, deadline: float) -> dict:
        import select

        while b"\0" not in self._buffer:
            left = deadline - time.monotonic()
            if left <= 0:
                raise TimeoutError("no answer from chromium")
            ready, _, _ = select.select([self._from_browser], [], [], left)
            if ready:
                chunk = os.read(self._from_browser, 1 << 16)
                if not chunk:
                    raise RuntimeError("chromium closed its DevTools pipe")
                self._buffer += chunk
        raw, self._buffer = self._buffer.split(b"\0", 1)
        return json.loads(raw)

    def _send(self, method: str, params: dict | None = None, session: str | None = None) -> dict:
        self._id += 1
        msg = {"id": self._id, "method": method, "params": params or {}}
        if session:
            msg["sessionId"] = session
        os.write(self._to_browser, json.dumps(msg).encode() + b"\0")
        deadline = time.monotonic() + self.timeout
        while True:
            reply = self._read_message(deadline)
            if reply.get("id") == self._id:
                if "error" in reply:
                    raise RuntimeError(f"{method}: {reply['error']}")
                return reply.get("result", {})
            self._events.append(reply)

    def _wait_for(self, method: str, session: str) -> dict:
        deadline = time.monotonic() + self.timeout
        while True:
            for i, ev in enumerate(self._events):
                if ev.get("method") == method and ev.get("sessionId") == session:
                    return self._events.pop(i)
            self._events.append(self._read_message(deadline))

    # -- pages ------------------------------------------------------------------------------
    def inspect(self, url: str) -> dict:
        target = self._send("Target.createTarget", {"url": "about:blank"})["targetId"]
        session = self._send("Target.attachToTarget", {"targetId": target, "flatten": True})["sessionId"]
        try:
            for domain in ("Page", "Network", "Runtime"):
                self._send(f"{domain}.enable", session=session)
            self._events.clear()
            nav = self._send("Page.navigate", {"url": url}, session=session)
            if nav.get("errorText"):
                return {"error": nav["errorText"], "images": [], "links": [], "ids": [], "failed": [url]}
            self._wait_for("Page.loadEventFired", session)
            value = self._send("Runtime.evaluate", {"expression": _INSPECT, "returnByValue": True},
                               session=session)["result"]["value"]
            page = json.loads(value)
            page["failed"] = [ev["params"].get("errorText", "") + " " + self._request_url(ev)
                              for ev in self._events if ev.get("method") == "Network.loadingFailed"
                              and ev.get("sessionId") == session]
            return page
        finally:
            self._send("Target.closeTarget", {"targetId": target})

    def _request_url(self, event: dict) -> str:
        rid = event["params"].get("requestId")
        for ev in self._events:
            if ev.get("method") == "Network.requestWillBeSent" and ev["params"].get("requestId") == rid:
                return ev["params"]["request"]["url"]
        return rid or ""


def crawl(browser: Browser, start: Path, root: Path) -> dict:
    """Load ``start`` and every HTML page under ``root`` it reaches through links; return
    {pages: n, problems: [...], external: n}. A problem: an image that did not load, a
    resource that failed, a link to a file that does not exist or leaves ``root``, a #anchor
    its page does not have."""
    root = root.resolve()
    pages: dict[Path, dict] = {}
    todo = [start.resolve()]
    problems, external, anchors = [], 0, []
    while todo:
        path = todo.pop()
        if path in pages:
            continue
        page = pages[path] = browser.inspect(path.as_uri())
        where = path.relative_to(root)
        if page.get("error"):
            problems.append(f"{where}: {page['error']}")
        problems += [f"{where}: image did not load: {img['src']}" for img in page["images"] if not img["ok"]]
        problems += [f"{where}: failed to load: {f}" for f in page["failed"]]
        for href in page["links"]:
            url, fragment = urldefrag(href)
            parsed = urlparse(url)
            if parsed.scheme in ("http", "https", "mailto"):
                external += 1
                continue
            if parsed.scheme != "file":
                problems.append(f"{where}: link with scheme {parsed.scheme!r}: {href}")
                continue
            target = Path(unquote(parsed.path))
            if target.is_dir():
                target = target / "index.html"
            if not target.exists():
                problems.append(f"{where}: link to a missing file: {href}")
            elif root not in target.resolve().parents and target.resolve() != root:
                problems.append(f"{where}: link leaves {root}: {href}")
            elif target.suffix == ".html":
                todo.append(target.resolve())
                if fragment:
                    anchors.append((where, target.resolve(), unquote(fragment)))
    for where, target, fragment in anchors:
        if target in pages and fragment not in pages[target]["ids"]:
            problems.append(f"{where}: no #{fragment} in {target.relative_to(root)}")
    return {"pages": len(pages), "problems": problems, "external": external,
            "images": sum(len(p["images"]) for p in pages.values())}
