"""Drive headless Chromium over the Chrome DevTools Protocol (standard library only).

The browser is started with --remote-debugging-pipe: it reads NUL-terminated
JSON commands on its fd 3 and writes NUL-terminated JSON replies and events on
its fd 4, so no websocket client is needed.

    base, server = serve("build-web/out")
    try:
        with Browser() as b:
            b.navigate(base + "/index.html")
            ok, renderer = b.webgl2_available()
            b.wait_for("window.peltReady === true")
            b.screenshot("/tmp/shot.png")
            assert not b.console_errors(), b.console_errors()
    finally:
        server.shutdown()

WebGL2 without a GPU goes through SwiftShader (software Vulkan) under ANGLE;
see WEBGL_FLAGS.  Canvas read-backs (canvas.toDataURL()) made in a later task
than the drawing need getContext("webgl2", {preserveDrawingBuffer: true}).
"""

import base64
import fcntl
import functools
import http.server
import json
import os
import select
import shutil
import signal
import subprocess
import tempfile
import threading
import time

# Debian's /usr/bin/chromium-headless-shell is a `sh -e` wrapper that runs the
# real binary as its child (no exec): killing the wrapper would orphan the
# browser, so the real binary comes first.
CANDIDATES = (
    ("/usr/lib/chromium/chromium-headless-shell", ()),
    ("/usr/bin/chromium-headless-shell", ()),
    ("/usr/bin/chromium", ("--headless=new",)),
)

# WebGL2 on a machine without a GPU: ANGLE on SwiftShader (software Vulkan).
# Debian's headless shell 156 falls back to it even without these flags, but
# full Chromium turned the automatic software fallback off (Chromium 137+)
# unless --enable-unsafe-swiftshader is given, so all are passed explicitly.
WEBGL_FLAGS = (
    "--use-angle=swiftshader",
    "--enable-unsafe-swiftshader",
    "--ignore-gpu-blocklist",
    "--enable-webgl",
)

COMMON_FLAGS = (
    "--no-first-run",
    "--no-default-browser-check",
    "--disable-extensions",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--disable-dev-shm-usage",   # containers often have a tiny /dev/shm
    "--mute-audio",
    "--hide-scrollbars",
)


class CDPError(RuntimeError):
    """An error reply from the browser, a protocol failure or a browser exit."""


class JSError(CDPError):
    """The page's JavaScript threw during evaluate()."""


def find_browser():
    """(path, extra flags) of the first installed headless Chromium."""
    for path, flags in CANDIDATES:
        if os.access(path, os.X_OK):
            return path, flags
    raise FileNotFoundError("no Chromium found; tried "
                            + ", ".join(p for p, _ in CANDIDATES))


def _become_subreaper():
    """prctl(PR_SET_CHILD_SUBREAPER, 1) on Linux; a no-op where it fails."""
    try:
        import ctypes
        ctypes.CDLL(None, use_errno=True).prctl(36, 1, 0, 0, 0)
    except (OSError, AttributeError):
        pass


def _remote_text(obj):
    """Readable text of a Runtime.RemoteObject (a console.log argument)."""
    if "value" in obj:
        v = obj["value"]
        return v if isinstance(v, str) else json.dumps(v)
    return obj.get("description") or obj.get("unserializableValue") or obj.get("type", "")


def _exception_text(details):
    """Readable text of Runtime.ExceptionDetails."""
    exc = details.get("exception") or {}
    text = exc.get("description") or details.get("text", "exception")
    if details.get("url"):
        text += " (%s:%s:%s)" % (details["url"], details.get("lineNumber", 0) + 1,
                                 details.get("columnNumber", 0) + 1)
    return text


class Browser:
    def __init__(self, browser_path=None, width=800, height=600, extra_flags=()):
        if browser_path is None:
            browser_path, mode_flags = find_browser()
        else:  # the headless shell is headless anyway; full Chromium needs =new
            mode_flags = (() if "headless-shell" in os.path.basename(browser_path)
                          else ("--headless=new",))
        self.console = []      # (type, text) from Runtime.consoleAPICalled
        self.exceptions = []   # text of Runtime.exceptionThrown
        self.log_entries = []  # (level, text) from Log.entryAdded
        self._next_id = 0
        self._buf = b""
        self._replies = {}     # id -> reply not yet claimed
        self._loads = 0        # Page.loadEventFired count
        self._session = None
        self.proc = None
        self._to_browser = self._from_browser = None
        self._dir = tempfile.mkdtemp(prefix="pelt-cdp-")
        try:
            self._launch(browser_path, mode_flags, width, height, extra_flags)
            self._attach()
        except BaseException:
            self.close()
            raise

    # -- start-up ---------------------------------------------------------

    def _launch(self, path, mode_flags, width, height, extra_flags):
        args = [path, *(mode_flags or ("--headless",))]
        if os.geteuid() == 0:
            args.append("--no-sandbox")  # the sandbox refuses to run as root
        args += [*WEBGL_FLAGS, *COMMON_FLAGS,
                 "--user-data-dir=" + os.path.join(self._dir, "profile"),
                 "--window-size=%d,%d" % (width, height),
                 "--remote-debugging-pipe", *extra_flags, "about:blank"]
        # Two pipes: the browser reads commands from fd 3 and writes to fd 4.
        cmd_r, cmd_w = os.pipe()
        out_r, out_w = os.pipe()
        # Copies at fd >= 10 so the dup2 onto 3 and 4 below cannot clobber them.
        child_in = fcntl.fcntl(cmd_r, fcntl.F_DUPFD_CLOEXEC, 10)
        child_out = fcntl.fcntl(out_w, fcntl.F_DUPFD_CLOEXEC, 10)
        os.close(cmd_r)
        os.close(out_w)

        def preexec():  # in the child, before close_fds keeps only 3 and 4
            os.dup2(child_in, 3)
            os.dup2(child_out, 4)

        # The browser's zygote helpers are orphaned when it exits; becoming
        # their subreaper lets close() reap them (PID 1 in a container may
        # not).  This marks the whole Python process; harmless in a test.
        _become_subreaper()
        self._log_path = os.path.join(self._dir, "browser.log")
        try:
            with open(self._log_path, "wb") as log:
                self.proc = subprocess.Popen(
                    args, stdin=subprocess.DEVNULL, stdout=log, stderr=log,
                    pass_fds=(3, 4), preexec_fn=preexec,
                    start_new_session=True)  # own process group: killpg at close
        finally:
            os.close(child_in)
            os.close(child_out)
        self._to_browser, self._from_browser = cmd_w, out_r

    def _attach(self):
        """Attach to the page target (flattened session) and enable the domains."""
        deadline = time.monotonic() + 30
        page = None
        while page is None:
            infos = self._send("Target.getTargets", {}, None, 30)["targetInfos"]
            page = next((t for t in infos if t["type"] == "page"), None)
            if page is None:
                if time.monotonic() > deadline:
                    page = {"targetId": self._send(
                        "Target.createTarget", {"url": "about:blank"}, None, 30)["targetId"]}
                else:
                    time.sleep(0.1)
        self._session = self._send("Target.attachToTarget",
                                   {"targetId": page["targetId"], "flatten": True},
                                   None, 30)["sessionId"]
        for domain in ("Runtime", "Page", "Log"):
            self.call(domain + ".enable")

    # -- protocol ---------------------------------------------------------

    def _send(self, method, params, session, timeout):
        """Send one command and wait for its reply; events are dispatched meanwhile."""
        if self.proc is None or self._to_browser is None:
            raise CDPError("browser is not running")
        self._next_id += 1
        msg_id = self._next_id
        msg = {"id": msg_id, "method": method, "params": params or {}}
        if session:
            msg["sessionId"] = session
        data = json.dumps(msg).encode() + b"\0"
        try:
            while data:
                data = data[os.write(self._to_browser, data):]
        except BrokenPipeError:
            raise CDPError("browser is gone (exit status %s), sending %s%s"
                           % (self.proc.poll(), method, self._log_tail())) from None
        deadline = time.monotonic() + timeout
        while msg_id not in self._replies:
            self._pump(deadline, "%s (%g s)" % (method, timeout))
        reply = self._replies.pop(msg_id)
        if "error" in reply:
            err = reply["error"]
            raise CDPError("%s failed: %s %s" % (method, err.get("message"),
                                                 err.get("data", "")))
        return reply.get("result", {})

    def _pump(self, deadline, what):
        """Read and dispatch what the browser has written; wait until the deadline."""
        left = deadline - time.monotonic()
        if left <= 0:
            raise TimeoutError("timed out waiting for " + what)
        ready, _, _ = select.select([self._from_browser], [], [], left)
        if not ready:
            return
        chunk = os.read(self._from_browser, 1 << 20)
        if not chunk:
            raise CDPError("browser closed the pipe (exit status %s) while waiting for %s%s"
                           % (self.proc.poll(), what, self._log_tail()))
        self._buf += chunk
        *messages, self._buf = self._buf.split(b"\0")
        for raw in messages:
            msg = json.loads(raw)
            if "id" in msg:
                self._replies[msg["id"]] = msg
            elif msg.get("sessionId") == self._session:
                self._event(msg["method"], msg.get("params", {}))

    def _event(self, method, p):
        if method == "Runtime.consoleAPICalled":
            self.console.append((p["type"], " ".join(_remote_text(a) for a in p.get("args", []))))
        elif method == "Runtime.exceptionThrown":
            self.exceptions.append(_exception_text(p["exceptionDetails"]))
        elif method == "Log.entryAdded":
            e = p["entry"]
            text = e.get("text", "")
            if e.get("url"):
                text += " (%s)" % e["url"]
            self.log_entries.append((e.get("level"), text))
        elif method == "Page.loadEventFired":
            self._loads += 1

    def _log_tail(self, n=2000):
        try:
            with open(self._log_path, "rb") as f:
                tail = f.read()[-n:].decode(errors="replace")
            return "\nbrowser output:\n" + tail if tail else ""
        except OSError:
            return ""

    # -- public API -------------------------------------------------------

    def call(self, method, params=None, timeout=30):
        """Send a command on the page session; return its result dict."""
        return self._send(method, params, self._session, timeout)

    def navigate(self, url, timeout=60):
        """Load url and wait for the page's load event."""
        loads = self._loads
        deadline = time.monotonic() + timeout
        res = self.call("Page.navigate", {"url": url}, timeout)
        if res.get("errorText"):
            raise CDPError("navigating to %s: %s" % (url, res["errorText"]))
        while self._loads == loads:
            self._pump(deadline, "the load event of " + url)

    def evaluate(self, expression, await_promise=False, timeout=60):
        """Evaluate a JS expression in the page; return its value (JSON-able)."""
        res = self.call("Runtime.evaluate",
                        {"expression": expression, "returnByValue": True,
                         "awaitPromise": await_promise}, timeout)
        if "exceptionDetails" in res:
            raise JSError("%s threw: %s" % (expression, _exception_text(res["exceptionDetails"])))
        return res["result"].get("value")  # undefined -> None

    def wait_for(self, expression, timeout=60, poll=0.1):
        """Poll a JS expression until it is truthy; return its value."""
        deadline = time.monotonic() + timeout
        while True:
            value = self.evaluate(expression, timeout=max(deadline - time.monotonic(), 1))
            if value:
                return value
            if time.monotonic() + poll > deadline:
                raise TimeoutError("%s still %r after %g s" % (expression, value, timeout))
            # Sleep by reading the pipe, so events keep arriving.
            until = time.monotonic() + poll
            while time.monotonic() < until:
                try:
                    self._pump(until, "nothing")
                except TimeoutError:
                    break

    def screenshot(self, path):
        """Write a PNG of the viewport to path."""
        data = self.call("Page.captureScreenshot", {"format": "png"}, 60)["data"]
        with open(path, "wb") as f:
            f.write(base64.b64decode(data))

    def webgl2_available(self):
        """(True, renderer string) when the page can make a WebGL2 context, else (False, why)."""
        ok, info = self.evaluate("""(() => {
            const gl = document.createElement('canvas').getContext('webgl2');
            if (!gl) return [false, 'getContext("webgl2") returned null'];
            const ext = gl.getExtension('WEBGL_debug_renderer_info');
            const r = ext ? gl.getParameter(ext.UNMASKED_RENDERER_WEBGL)
                          : gl.getParameter(gl.RENDERER);
            gl.getExtension('WEBGL_lose_context')?.loseContext();
            return [true, String(r)];
        })()""")
        return ok, info

    def console_errors(self):
        """console.error/assert messages, uncaught exceptions and error log entries."""
        return ([t for kind, t in self.console if kind in ("error", "assert")]
                + list(self.exceptions)
                + [t for level, t in self.log_entries if level == "error"])

    def close(self):
        """Close the browser (politely, then by force) and remove its profile."""
        if self.proc is not None:
            if self.proc.poll() is None and self._to_browser is not None:
                try:
                    self._send("Browser.close", {}, None, 5)
                except (CDPError, TimeoutError, OSError):
                    pass
            try:
                self.proc.wait(10)
            except subprocess.TimeoutExpired:
                self._signal_group(signal.SIGTERM)
                try:
                    self.proc.wait(5)
                except subprocess.TimeoutExpired:
                    pass
            self._signal_group(signal.SIGKILL)  # whatever helper is left
            self.proc.wait()
            self._reap_group()
        for fd in (self._to_browser, self._from_browser):
            if fd is not None:
                os.close(fd)
        self._to_browser = self._from_browser = None
        self.proc = None
        shutil.rmtree(self._dir, ignore_errors=True)

    def _signal_group(self, sig):
        try:
            os.killpg(self.proc.pid, sig)
        except (ProcessLookupError, PermissionError):
            pass

    def _reap_group(self, timeout=5):
        """Reap the browser's orphaned helpers (we are their subreaper)."""
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            try:
                while os.waitpid(-self.proc.pid, os.WNOHANG)[0]:
                    pass
            except ChildProcessError:
                pass
            try:
                os.killpg(self.proc.pid, 0)  # anyone (zombies too) left in the group?
            except (ProcessLookupError, PermissionError):
                return
            time.sleep(0.02)

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()


class _QuietHandler(http.server.SimpleHTTPRequestHandler):
    extensions_map = {**http.server.SimpleHTTPRequestHandler.extensions_map,
                      ".wasm": "application/wasm", ".js": "text/javascript",
                      ".mjs": "text/javascript"}

    def log_message(self, *args):
        pass


def serve(directory):
    """Serve directory on 127.0.0.1 (a free port) in a daemon thread.

    Returns (base_url, server); call server.shutdown() when done.
    """
    handler = functools.partial(_QuietHandler, directory=os.fspath(directory))
    server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), handler)
    server.daemon_threads = True
    threading.Thread(target=server.serve_forever, daemon=True).start()
    return "http://127.0.0.1:%d" % server.server_address[1], server
