// The page around `pelt view` in the browser (docs/web.md). Emscripten puts
// this in front of its own code (--pre-js), inside the Module's scope.
//
// URL parameters:
//   scene=NAME     a bundled scene (scenes/NAME), "dropped" (the last scene
//                  dropped on the page) or a URL of a scene file
//   preset=NAME    a curl look (--preset)
//   size=WxH       a canvas of that size (default: the window, following it)
//   script=URL     timed input, the format of `pelt view --script`
//   hud=0          start with the HUD hidden
//   args=...       more flags of `pelt view`, separated by spaces
//   sync=1         wait for each frame's pixels before timing it (a 1-pixel
//                  read), so the readout is the frame's cost, not the pace
//                  at which the browser hands out animation frames
// window.pelt is the scripting hook: ready, frames, exitCode, error, log,
// frameMs(), capture() (a PNG data URL of the next frame), readFile(path),
// downloads (the files handed to the browser).
(function () {
  'use strict';
  const params = new URLSearchParams(location.search);
  const $ = (id) => document.getElementById(id);
  const canvas = $('canvas');
  const pelt = (window.pelt = {
    ready: false,      // a frame has been drawn
    frames: 0,
    exitCode: null,    // main's, once it has returned
    error: '',         // what the error box shows
    log: [],           // every line pelt printed
    intervals: [],     // ms between the last frames (the page's frame time)
    work: [],          // ms each frame's own work took (the viewer's frame function)
  });
  const fixedSize = /^(\d+)x(\d+)$/.exec(params.get('size') || '');

  function showError(text) {
    pelt.error = text;
    const box = $('pelt-error');
    box.textContent = text;
    box.style.display = 'block';
    $('pelt-status').textContent = 'stopped';
  }

  function fitCanvas() {
    const w = fixedSize ? +fixedSize[1] : Math.max(1, window.innerWidth);
    const h = fixedSize ? +fixedSize[2] : Math.max(1, window.innerHeight);
    if (canvas.width !== w || canvas.height !== h) { canvas.width = w; canvas.height = h; }
    canvas.style.width = w + 'px';
    canvas.style.height = h + 'px';
  }
  fitCanvas();
  window.addEventListener('resize', fitCanvas); // the viewer follows the canvas

  const median = (v) => { const s = v.slice().sort((a, b) => a - b); return s.length ? s[s.length >> 1] : 0; };
  pelt.frameMs = () => median(pelt.intervals);
  pelt.workMs = () => median(pelt.work);

  // A PNG of the next frame, read in the same animation frame it was drawn in.
  let captures = [];
  pelt.capture = () => new Promise((resolve) => captures.push(resolve));
  pelt.exists = (path) => FS.analyzePath(path).exists;
  // A file the viewer wrote (a script's screenshot), as a data URL.
  pelt.readFile = (path) => {
    const bytes = FS.readFile(path);
    let s = '';
    for (let i = 0; i < bytes.length; i += 0x8000) s += String.fromCharCode.apply(null, bytes.subarray(i, i + 0x8000));
    return 'data:application/octet-stream;base64,' + btoa(s);
  };

  let frameStart = 0, lastEnd = 0;
  Module.canvas = canvas;
  // What the viewer saves (P: a screenshot, Ctrl+S: the groom) lands in the
  // page's in-memory files; the page hands it to the browser as a download.
  pelt.downloads = [];
  function offerDownload(path) {
    if (!FS.analyzePath(path).exists) return;
    const a = document.createElement('a');
    a.href = URL.createObjectURL(new Blob([FS.readFile(path)]));
    a.download = path.split('/').pop();
    document.body.appendChild(a);
    a.click();
    a.remove();
    setTimeout(() => URL.revokeObjectURL(a.href), 10000);
    pelt.downloads.push(a.download);
  }
  Module.print = (text) => { pelt.log.push(text); console.log(text); };
  Module.printErr = (text) => {
    pelt.log.push(text);
    console.log(text);
    const saved = /^pelt view: (?:screenshot|groom saved to) (.+)$/.exec(text);
    if (saved) offerDownload(saved[1]);
  };
  Module.onAbort = (what) => showError('pelt stopped: ' + what);
  Module.preMainLoop = () => { frameStart = performance.now(); };
  const syncFrames = params.get('sync') === '1', onePixel = new Uint8Array(4);
  Module.postMainLoop = () => {
    if (syncFrames && Module.ctx) Module.ctx.readPixels(0, 0, 1, 1, Module.ctx.RGBA, Module.ctx.UNSIGNED_BYTE, onePixel);
    const now = performance.now();
    pelt.work.push(now - frameStart);
    if (lastEnd) pelt.intervals.push(now - lastEnd);
    lastEnd = now;
    if (pelt.work.length > 120) pelt.work.shift();
    if (pelt.intervals.length > 120) pelt.intervals.shift();
    pelt.frames++;
    pelt.ready = true;
    if (captures.length) {
      const url = canvas.toDataURL('image/png');
      captures.splice(0).forEach((r) => r(url));
    }
    if (pelt.frames % 10 === 0)
      $('pelt-ms').textContent = pelt.frameMs().toFixed(1) + ' ms a frame (' + pelt.workMs().toFixed(1) + ' ms drawing)';
  };

  // Files the run needs, fetched before main: the script, a scene by URL.
  async function fetchInto(url, path) {
    const r = await fetch(url);
    if (!r.ok) throw new Error('cannot fetch ' + url + ': HTTP ' + r.status);
    FS.writeFile(path, new Uint8Array(await r.arrayBuffer()));
  }
  let scenePath = null;
  Module.preRun = Module.preRun || [];
  Module.preRun.push(() => {
    addRunDependency('pelt-page');
    const jobs = [];
    FS.mkdir('/page');
    const scene = params.get('scene');
    if (scene === 'dropped') {
      const text = sessionStorage.getItem('pelt-dropped-scene');
      if (text !== null) { FS.writeFile('/page/dropped.json', text); scenePath = '/page/dropped.json'; }
    } else if (scene && /^[\w.-]+\.json$/.test(scene)) {
      scenePath = '/scenes/' + scene;
    } else if (scene) {
      // Under its own name, so that messages name the file the user gave.
      scenePath = '/page/' + (scene.split(/[?#]/)[0].split('/').pop() || 'scene.json');
      jobs.push(fetchInto(scene, scenePath));
    }
    if (params.get('script')) jobs.push(fetchInto(params.get('script'), '/page/script.txt'));
    Promise.all(jobs).then(() => removeRunDependency('pelt-page'),
                           (e) => showError(String(e.message || e)));
  });

  Module.onRuntimeInitialized = () => {
    // The panel's scene list: the bundled scenes.
    const select = $('pelt-scene');
    for (const name of FS.readdir('/scenes').filter((n) => n.endsWith('.json')).sort()) {
      const o = document.createElement('option');
      o.value = o.textContent = name;
      select.appendChild(o);
    }
    select.value = params.get('scene') || '';
    $('pelt-preset').value = params.get('preset') || '';
    const args = []; // of `pelt view` (apps/web_main.c)
    if (scenePath) args.push(scenePath);
    args.push('--size', canvas.width + 'x' + canvas.height);
    if (params.get('preset')) args.push('--preset', params.get('preset'));
    if (params.get('script')) args.push('--script', '/page/script.txt');
    if (params.get('hud') === '0') args.push('--no-hud');
    if (params.get('args')) args.push(...params.get('args').split(' ').filter(Boolean));
    $('pelt-status').textContent = 'pelt view ' + args.join(' ');
    canvas.focus();
    const rc = callMain(args);
    if (typeof rc === 'number' && rc !== 0) { // undefined: the frames go on
      pelt.exitCode = rc;
      const lines = pelt.log.filter((l) => /^pelt/.test(l));
      showError((lines.length ? lines : pelt.log).join('\n') || 'pelt view ended with status ' + rc);
    }
  };

  // The panel: a new scene or curl reloads the page with it; tools press keys.
  function reloadWith(key, value) {
    const p = new URLSearchParams(location.search);
    if (value) p.set(key, value); else p.delete(key);
    location.search = p.toString();
  }
  // (The page's elements come before this script: no need to wait for them.)
  $('pelt-scene').addEventListener('change', (e) => reloadWith('scene', e.target.value));
  $('pelt-preset').addEventListener('change', (e) => reloadWith('preset', e.target.value));
  for (const b of document.querySelectorAll('#panel button[data-key]'))
    b.addEventListener('click', () => { Module._pelt_web_key(+b.dataset.key, 0); canvas.focus(); });

  // Drops: a scene file restarts the page with it; meshes go to the viewer
  // (Emscripten's GLFW writes them to the page's files and calls its drop).
  const dropHint = $('pelt-drop');
  window.addEventListener('dragover', (e) => { e.preventDefault(); dropHint.style.display = 'block'; });
  window.addEventListener('dragleave', () => { dropHint.style.display = 'none'; });
  window.addEventListener('drop', (e) => {
    dropHint.style.display = 'none';
    const f = e.dataTransfer && e.dataTransfer.files[0];
    if (!f || !f.name.toLowerCase().endsWith('.json')) return;
    e.preventDefault();
    e.stopImmediatePropagation();
    f.text().then((text) => {
      sessionStorage.setItem('pelt-dropped-scene', text);
      reloadWith('scene', 'dropped');
    });
  }, true);

  // Esc closes the desktop's window; a page has nothing to close, and the
  // viewer would stop drawing: the page keeps it from the viewer.
  window.addEventListener('keydown', (e) => {
    if (e.key === 'Escape') e.stopImmediatePropagation();
  }, true);

  // The wheel, in clicks as on the desktop (a notch is 100 pixels or 3
  // lines), ahead of Emscripten's GLFW, which would pass the raw pixels on.
  canvas.addEventListener('wheel', (e) => {
    e.preventDefault();
    e.stopImmediatePropagation();
    const clicks = -e.deltaY / (e.deltaMode === 0 ? 100 : e.deltaMode === 1 ? 3 : 1);
    Module._pelt_web_scroll(Math.max(-3, Math.min(3, clicks)));
  }, { capture: true, passive: false });

  // Touch: one finger drags as the left button (the tool, or orbit on the
  // background), two fingers pinch to zoom as the wheel does.
  let pinch = 0;
  const mouse = (type, t, button) => canvas.dispatchEvent(new MouseEvent(type, {
    clientX: t.clientX, clientY: t.clientY, button: button, buttons: type === 'mouseup' ? 0 : 1, bubbles: true }));
  const spread = (ts) => Math.hypot(ts[0].clientX - ts[1].clientX, ts[0].clientY - ts[1].clientY);
  canvas.addEventListener('touchstart', (e) => {
    e.preventDefault();
    if (e.touches.length === 1) mouse('mousedown', e.touches[0], 0);
    else if (e.touches.length === 2) { mouse('mouseup', e.touches[0], 0); pinch = spread(e.touches); }
  }, { passive: false });
  canvas.addEventListener('touchmove', (e) => {
    e.preventDefault();
    if (e.touches.length === 1) mouse('mousemove', e.touches[0], 0);
    else if (e.touches.length === 2 && pinch) {
      const d = spread(e.touches);
      Module._pelt_web_scroll(Math.log(d / pinch) / Math.log(1 / 0.9)); // the distance follows the fingers
      pinch = d;
    }
  }, { passive: false });
  canvas.addEventListener('touchend', (e) => {
    e.preventDefault();
    if (e.touches.length === 0 && !pinch) mouse('mouseup', e.changedTouches[0], 0);
    if (e.touches.length === 0) pinch = 0;
  }, { passive: false });
})();
