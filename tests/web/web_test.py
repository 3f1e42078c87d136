#!/usr/bin/env python3
"""The browser build in a real browser (docs/web.md, "The test").

Serves build-web on 127.0.0.1, opens pelt.html in Debian's headless Chromium
over the DevTools protocol (tests/web/cdp.py) and checks:
  1. the default scene's first frame against the native `pelt render` of the
     same scene at the same size: mean difference at most MAX_MEAN_DIFF of 255;
  2. a scripted water click makes the fur around it darker and clumped;
  3. a comb stroke turns the hair under it (to the right, then to the left);
  4. a broken scene file shows a readable error on the page;
  5. a mesh dropped on the page loads, a broken one is refused with a message;
  6. the wheel and a two-finger pinch zoom in;
  7. no console errors on any of those pages;
and measures the page's frame time against native `pelt bench` on the same
scene and size. Exit 77 (skipped) only where the browser has no WebGL2.

usage: web_test.py --web build-web --pelt build/pelt --out DIR
"""

import argparse
import base64
import json
import math
import os
import re
import shutil
import struct
import subprocess
import sys
import time
import zlib

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import cdp  # noqa: E402

W, H = 400, 300
MAX_MEAN_DIFF = 3.0   # of 255, RGB: two GL implementations, one picture
FAILURES = []


def check(name, ok, detail):
    print("%s %s: %s" % ("ok  " if ok else "FAIL", name, detail), flush=True)
    if not ok:
        FAILURES.append(name)


# ---- PNG: 8-bit RGB/RGBA, not interlaced (what stb and Chromium write) -------

def read_png(data):
    """(width, height, rows of RGB tuples) of PNG bytes."""
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise ValueError("not a PNG")
    pos, idat, w = 8, b"", 0
    while pos < len(data):
        n, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        pos += 12 + n
        if kind == b"IHDR":
            w, h, depth, ctype, _, _, interlace = struct.unpack(">IIBBBBB", body)
            if depth != 8 or ctype not in (2, 6) or interlace:
                raise ValueError("unsupported PNG (depth %d, type %d)" % (depth, ctype))
            bpp = 3 if ctype == 2 else 4
        elif kind == b"IDAT":
            idat += body
    raw = zlib.decompress(idat)
    stride = w * bpp
    rows, prev = [], bytearray(stride)
    for y in range(h):
        f = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):  # the five PNG filters (RFC 2083, 6.)
            a = line[i - bpp] if i >= bpp else 0
            b = prev[i]
            c = prev[i - bpp] if i >= bpp else 0
            if f == 1:
                line[i] = (line[i] + a) & 255
            elif f == 2:
                line[i] = (line[i] + b) & 255
            elif f == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append([tuple(line[x * bpp:x * bpp + 3]) for x in range(w)])
        prev = line
    return w, h, rows


def luma(p):
    return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]


def region(rows, cx, cy, r):
    return [[luma(rows[y][x]) for x in range(cx - r, cx + r)] for y in range(cy - r, cy + r)]


def mean(v):
    return sum(v) / len(v)


def mean_luma(reg):
    return mean([v for row in reg for v in row])


def row_correlation(reg, lag):
    """Pearson correlation of each pixel's luminance with the one `lag` pixels
    to its right: fine hair decorrelates within a pixel or two, tufts that
    gather it stay correlated over several. Darkening alone leaves it."""
    a = [row[x] for row in reg for x in range(len(row) - lag)]
    b = [row[x + lag] for row in reg for x in range(len(row) - lag)]
    ma, mb = mean(a), mean(b)
    cov = mean([(p - ma) * (q - mb) for p, q in zip(a, b)])
    va, vb = mean([(p - ma) ** 2 for p in a]), mean([(q - mb) ** 2 for q in b])
    return cov / (va * vb) ** 0.5 if va > 0 and vb > 0 else 0.0


def orientation(reg):
    """Dominant image direction in degrees [0, 180) from the structure tensor:
    the direction along the hairs (the gradient runs across them)."""
    jxx = jyy = jxy = 0.0
    for y in range(1, len(reg) - 1):
        for x in range(1, len(reg[0]) - 1):
            gx = (reg[y][x + 1] - reg[y][x - 1]) / 2
            gy = (reg[y + 1][x] - reg[y - 1][x]) / 2
            jxx += gx * gx
            jyy += gy * gy
            jxy += gx * gy
    gradient = 0.5 * math.atan2(2 * jxy, jxx - jyy)  # image y down
    along = math.degrees(gradient) + 90.0
    return along % 180.0


def angle_between(a, b):
    d = abs(a - b) % 180.0
    return min(d, 180.0 - d)


# ---- the page ----------------------------------------------------------------

def open_page(b, base, query, timeout=240):
    # The load event waits for the page before to unload, and a zoomed-in
    # frame of it on a software GPU can take a minute on a slow machine: the
    # navigation gets the page's whole timeout, not cdp's 60 s.
    b.navigate(base + "/pelt.html?" + query, timeout)
    b.wait_for("window.pelt && (window.pelt.ready || window.pelt.error)", timeout=timeout)
    err = b.evaluate("window.pelt.error")
    if err:
        raise RuntimeError("the page shows an error: " + err)


def page_file(b, path, timeout=600):
    """Bytes of a file the viewer wrote in the page (a script's screenshot)."""
    b.wait_for("window.pelt.error || window.pelt.exists(%s)" % json.dumps(path), timeout=timeout)
    url = b.evaluate("window.pelt.readFile(%s)" % json.dumps(path))
    return base64.b64decode(url.split(",", 1)[1])


def save(out, name, data):
    """Keeps a picture of the run (the docs' come from here)."""
    with open(os.path.join(out, name), "wb") as f:
        f.write(data)


def write_script(directory, name, lines):
    with open(os.path.join(directory, name), "w") as f:
        f.write("\n".join(lines) + "\n")
    return "test-scripts/" + name


def drop_file(b, name, text):
    """Drops a file on the canvas, as a user dragging it from their desktop."""
    b.evaluate("(() => { const dt = new DataTransfer(); dt.items.add(new File([%s], %s));"
               " document.getElementById('canvas').dispatchEvent(new DragEvent('drop',"
               " {dataTransfer: dt, bubbles: true, cancelable: true})); })()"
               % (json.dumps(text), json.dumps(name)))


def fur_share(b):
    """Share of the next frames' pixels that are not the background (two
    frames on, so that input given before the call is drawn)."""
    frames = b.evaluate("window.pelt.frames")
    b.wait_for("window.pelt.frames > %d" % (frames + 2), timeout=300)
    url = b.evaluate("window.pelt.capture()", await_promise=True, timeout=300)
    _, _, rows = read_png(base64.b64decode(url.split(",", 1)[1]))
    bg = rows[0][0]
    flat = [p for row in rows for p in row]
    return sum(max(abs(p[c] - bg[c]) for c in range(3)) > 12 for p in flat) / len(flat)


def no_console_errors(b, what):
    errors = b.console_errors()
    check("console_" + what, not errors, "no console errors" if not errors else "; ".join(errors))


def native_bench_ms(pelt, size):
    """Median ms a frame of `pelt bench` on the default scene."""
    out = subprocess.run([pelt, "bench", "--size", size, "--frames", "10", "--msaa", "0"],
                         capture_output=True, text=True, timeout=900)
    m = re.search(r"as drawn\s+median\s+([\d.]+) ms", out.stdout + out.stderr)
    if not m:
        raise RuntimeError("pelt bench printed no median:\n" + out.stdout + out.stderr)
    return float(m.group(1))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--web", required=True, help="the build directory with pelt.html")
    ap.add_argument("--pelt", required=True, help="the native pelt command")
    ap.add_argument("--out", required=True, help="where pictures and figures go")
    o = ap.parse_args()
    web, out = os.path.abspath(o.web), os.path.abspath(o.out)
    for f in ("pelt.html", "pelt.js", "pelt.wasm", "pelt.data"):
        if not os.path.exists(os.path.join(web, f)):
            print("web_test: %s missing: build it with scripts/web.sh" % os.path.join(web, f))
            return 1
    os.makedirs(out, exist_ok=True)
    scripts = os.path.join(web, "test-scripts")
    shutil.rmtree(scripts, ignore_errors=True)
    os.makedirs(scripts)

    # The native picture of the default scene, at the page's size.
    native_png = os.path.join(out, "native_default.png")
    subprocess.run([o.pelt, "render", "--size", "%dx%d" % (W, H), "--msaa", "0", "-o", native_png],
                   check=True, capture_output=True, timeout=600)

    base, server = cdp.serve(web)
    try:
        with cdp.Browser(width=W + 300, height=H + 200) as b:
            ok, info = b.webgl2_available()
            if not ok:
                print("web_test: SKIPPED: this browser cannot create a WebGL2 context (%s)" % info)
                return 77
            print("web_test: WebGL2 through %s" % info, flush=True)
            fixed = "size=%dx%d&hud=0&args=%s" % (W, H, "--msaa%200")

            # 1. The default scene's first frame against native render.
            s = write_script(scripts, "default.txt", ["0 screenshot /page/default.png"])
            t0 = time.time()
            open_page(b, base, fixed + "&script=" + s)
            first = page_file(b, "/page/default.png")
            print("web_test: the page's first frame in %.1f s" % (time.time() - t0), flush=True)
            save(out, "web_default.png", first)
            canvas = b.evaluate("window.pelt.capture()", await_promise=True, timeout=120)
            save(out, "web_canvas.png", base64.b64decode(canvas.split(",", 1)[1]))
            _, _, a = read_png(first)
            with open(native_png, "rb") as f:
                _, _, n = read_png(f.read())
            diff = mean([abs(a[y][x][c] - n[y][x][c]) for y in range(H) for x in range(W) for c in range(3)])
            check("default_matches_native", diff <= MAX_MEAN_DIFF,
                  "mean difference %.2f of 255 (at most %.1f) against pelt render" % (diff, MAX_MEAN_DIFF))
            no_console_errors(b, "default")

            # 2. Water: a click on the ring's lower left, then 2 s of clumping.
            cx, cy = 130, 200
            s = write_script(scripts, "water.txt", [
                "0 screenshot /page/dry.png", "0.1 key 1", "0.2 click %d %d" % (cx, cy),
                "0.4 click %d %d" % (cx + 12, cy - 6), "2.0 screenshot /page/wet.png"])
            open_page(b, base, fixed + "&script=" + s)
            _, _, dry = read_png(page_file(b, "/page/dry.png"))
            wet_bytes = page_file(b, "/page/wet.png")
            _, _, wet = read_png(wet_bytes)
            save(out, "web_water.png", wet_bytes)
            rd, rw = region(dry, cx, cy, 24), region(wet, cx, cy, 24)
            ld, lw = mean_luma(rd), mean_luma(rw)
            cd, cw = row_correlation(rd, 4), row_correlation(rw, 4)
            check("water_darkens", lw <= 0.9 * ld,
                  "mean luminance around the click %.1f -> %.1f (at most 0.9x)" % (ld, lw))
            check("water_clumps", cw >= cd + 0.1,
                  "luminance correlation 4 px apart (tufts wider than hairs) %.3f -> %.3f (at least +0.1)" % (cd, cw))
            b.screenshot(os.path.join(out, "page_water.png"))
            no_console_errors(b, "water")

            # 3. The comb: a stroke to the right, then one to the left, across
            # the front of the ring, where the hair hangs down (90 degrees).
            px, py = 200, 225
            strokes = {}
            for name, (x0, x1) in (("right", (px - 19, px + 19)), ("left", (px + 19, px - 19))):
                s = write_script(scripts, "comb_%s.txt" % name, [
                    "0 screenshot /page/before.png", "0 key 3",
                    "0 drag %d %d %d %d 0.2" % (x0, py, x1, py), "0.3 screenshot /page/after.png"])
                open_page(b, base, fixed + "&script=" + s)
                _, _, before = read_png(page_file(b, "/page/before.png"))
                after_bytes = page_file(b, "/page/after.png")
                _, _, after = read_png(after_bytes)
                if name == "right":
                    save(out, "web_comb.png", after_bytes)
                strokes[name] = (orientation(region(before, px, py, 20)), orientation(region(after, px, py, 20)))
            (b0, right), (_, left) = strokes["right"], strokes["left"]
            check("comb_moves_hair", angle_between(b0, right) >= 15.0 and angle_between(b0, left) >= 15.0,
                  "hair direction under the comb %.0f deg -> %.0f (right) / %.0f (left); at least 15 deg"
                  % (b0, right, left))
            check("comb_follows_stroke", (right - b0) * (left - b0) < 0,
                  "the strokes lean the hair to opposite sides of %.0f deg: %.0f and %.0f" % (b0, right, left))
            no_console_errors(b, "comb")

            # 4. A broken scene file: a readable error on the page.
            with open(os.path.join(scripts, "broken.json"), "w") as f:
                f.write('{ "fur": { "layers": 16, } \n')
            b.navigate(base + "/pelt.html?scene=test-scripts/broken.json")
            b.wait_for("window.pelt.error", timeout=120)
            err = b.evaluate("window.pelt.error")
            shown = b.evaluate("getComputedStyle(document.getElementById('pelt-error')).display !== 'none'"
                               " && document.getElementById('pelt-error').textContent")
            check("broken_scene_error", bool(shown) and "broken.json" in err,
                  "the page says: %s" % err.replace("\n", " | "))
            b.screenshot(os.path.join(out, "page_error.png"))
            no_console_errors(b, "broken_scene")

            # 5. Drops: a mesh loads into the running viewer; a broken one is
            # refused with a message naming it, and the scene stays.
            open_page(b, base, fixed)
            mesh = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scenes",
                                "meshes", "sphere-and-box.obj")
            with open(mesh) as f:
                drop_file(b, "sphere-and-box.obj", f.read())
            b.wait_for("window.pelt.log.some((l) => /loaded .*sphere-and-box.obj/.test(l))", timeout=300)
            drop_file(b, "broken.obj", "v 0 0 0\nf 1 2 9\n")
            b.wait_for("window.pelt.log.some((l) => /broken.obj: line 2/.test(l))", timeout=300)
            frames = b.evaluate("window.pelt.frames")
            b.wait_for("window.pelt.frames > %d" % (frames + 2), timeout=300)
            said = [l for l in b.evaluate("window.pelt.log") if "broken.obj" in l]
            b.evaluate("Module._pelt_web_key(80, 0)")  # P: a screenshot, handed over as a download
            b.wait_for("window.pelt.downloads.length > 0", timeout=300)
            got = b.evaluate("window.pelt.downloads")
            check("screenshot_download", got == ["pelt-view-000.png"],
                  "P hands the browser %s" % got)
            check("drop_mesh", not b.evaluate("window.pelt.error"),
                  "sphere-and-box.obj loaded; the broken mesh refused (%s), frames go on" % said[-1])
            no_console_errors(b, "drop")

            # 6. Zoom by the wheel and by a pinch: the ring fills more of the canvas.
            open_page(b, base, fixed)
            shares = [fur_share(b)]
            b.call("Input.dispatchMouseEvent", {"type": "mouseWheel", "x": 200, "y": 150,
                                                "deltaX": 0, "deltaY": -200})
            shares.append(fur_share(b))
            b.call("Emulation.setTouchEmulationEnabled", {"enabled": True, "maxTouchPoints": 2})
            b.call("Input.dispatchTouchEvent", {"type": "touchStart",
                                                "touchPoints": [{"x": 170, "y": 150}, {"x": 230, "y": 150}]})
            for i in range(1, 6):
                b.call("Input.dispatchTouchEvent", {"type": "touchMove", "touchPoints": [
                    {"x": 170 - 6 * i, "y": 150}, {"x": 230 + 6 * i, "y": 150}]})
            b.call("Input.dispatchTouchEvent", {"type": "touchEnd", "touchPoints": []})
            shares.append(fur_share(b))
            check("zoom_wheel_and_pinch", shares[1] >= 1.15 * shares[0] and shares[2] >= 1.15 * shares[1],
                  "fur covers %.3f of the canvas, %.3f after two wheel notches in, %.3f after a pinch "
                  "spreading the fingers 2x (each at least 1.15x the last)" % tuple(shares))
            no_console_errors(b, "zoom")
            b.call("Input.dispatchKeyEvent", {"type": "keyDown", "key": "Escape", "code": "Escape",
                                              "windowsVirtualKeyCode": 27})
            b.call("Input.dispatchKeyEvent", {"type": "keyUp", "key": "Escape", "code": "Escape",
                                              "windowsVirtualKeyCode": 27})
            frames = b.evaluate("window.pelt.frames")
            try:
                b.wait_for("window.pelt.frames > %d" % (frames + 3), timeout=120)
                going = True
            except TimeoutError:
                going = False
            check("escape_keeps_drawing", going, "the frames go on after Esc" if going else "Esc stopped the viewer")

            # 7. Speed: the page live (no script) against native pelt bench.
            open_page(b, base, "size=%dx%d&sync=1&args=%s" % (W, H, "--msaa%200"))
            b.wait_for("window.pelt.intervals.length >= 20", timeout=900)
            web_ms = b.evaluate("window.pelt.frameMs()")
            work_ms = b.evaluate("window.pelt.workMs()")
            b.screenshot(os.path.join(out, "page_default.png"))
            no_console_errors(b, "live")
    finally:
        server.shutdown()
    native_ms = native_bench_ms(o.pelt, "%dx%d" % (W, H))
    speed = ("browser %.1f ms a frame (%.1f ms in the viewer's frame), native pelt bench %.1f ms: "
             "%.2fx" % (web_ms, work_ms, native_ms, web_ms / native_ms))
    print("web_test: speed: " + speed)
    with open(os.path.join(out, "speed.txt"), "w") as f:
        f.write(speed + "\n")
    if FAILURES:
        print("web_test: %d failed: %s" % (len(FAILURES), ", ".join(FAILURES)))
        return 1
    print("web_test: all passed; pictures in %s" % out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
