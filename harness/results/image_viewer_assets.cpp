// The image viewer's style sheet and script (results/image_viewer.h).
#include "results/image_viewer.h"

namespace sb::results {

namespace {

constexpr const char* kViewerStyle = R"css(
.viewer{background:var(--card);border:1px solid var(--line);border-radius:6px;padding:10px;margin:0 0 16px;outline:none}
.viewer:focus{border-color:#5b82c9;box-shadow:0 0 0 2px #c9d7f2}
.viewer-bar{display:flex;flex-wrap:wrap;align-items:center;gap:6px 12px;margin-bottom:8px;font-size:12.5px}
.viewer-bar button{font:inherit;padding:2px 8px;border:1px solid var(--line);border-radius:5px;background:#f3f5f9;cursor:pointer}
.viewer-bar button[aria-pressed=true]{background:#1d2330;color:#fff;border-color:#1d2330}
.viewer-bar button.b-side{box-shadow:inset 0 -3px 0 #d0342c}
.viewer-items button{font-family:ui-monospace,"DejaVu Sans Mono",monospace;font-size:12px}
.viewer kbd{font:11px ui-monospace,"DejaVu Sans Mono",monospace;color:var(--muted)}
.viewer-bar button[aria-pressed=true] kbd{color:#c8d0de}
.viewer-zoom{font-variant-numeric:tabular-nums;color:var(--muted);min-width:70px}
.viewer-stage{overflow:hidden;background:#2a2f3a;line-height:0;max-width:100%}
.viewer-canvas{display:block;cursor:crosshair;image-rendering:pixelated}
.viewer-split{display:block;margin:4px 0}
.viewer-split[hidden]{display:none}
.viewer-readout{font:12.5px ui-monospace,"DejaVu Sans Mono",monospace;margin-top:6px;min-height:1.5em;font-variant-numeric:tabular-nums}
)css";

constexpr const char* kViewerScript = R"js(
(function () {
  'use strict';
  var data = {}, waiting = {}, failed = {}, images = {};
  // Called by each data file (viewer/<viewer>-<item>.js).
  window.sbViewerData = function (key, d) {
    var out = {width: d.width, height: d.height, channels: d.channels};
    out.v = decode(d.v);
    if (d.sigma) { out.sigma = decode(d.sigma); out.sigmaChannels = d.sigma_channels; }
    if (d.measured) out.measured = bytes(d.measured);
    data[key] = out;
    (waiting[key] || []).forEach(function (f) { f(); });
    delete waiting[key];
  };
  function bytes(b64) {
    var s = atob(b64), out = new Uint8Array(s.length);
    for (var i = 0; i < s.length; ++i) out[i] = s.charCodeAt(i);
    return out;
  }
  function decode(b64) { return new Float32Array(bytes(b64).buffer); }
  // Loads a data file once; `done` runs when it arrives (not when it is
  // already here: the caller draws anyway, and drawing is what asks).
  function loadData(src, done) {
    if (data[src] || failed[src]) return;
    if (waiting[src]) { waiting[src].push(done); return; }
    waiting[src] = [done];
    var s = document.createElement('script');
    s.src = src;
    s.onerror = function () {
      failed[src] = true;
      console.error('missing viewer data: ' + src);
      (waiting[src] || []).forEach(function (f) { f(); });
      delete waiting[src];
    };
    document.head.appendChild(s);
  }
  function image(src, redraw) {
    var entry = images[src];
    if (!entry) {
      entry = images[src] = {img: new Image(), ok: false, bad: false, waiting: []};
      entry.img.onload = function () {
        entry.ok = true;
        entry.waiting.forEach(function (f) { f(); });
      };
      entry.img.onerror = function () {
        entry.bad = true;
        console.error('missing image: ' + src);
        entry.waiting.forEach(function (f) { f(); });
      };
      entry.img.src = src;
    }
    if (!entry.ok && !entry.bad) entry.waiting.push(redraw);
    return entry;
  }
  function fmt(x) {
    if (x === undefined) return '\u2013';
    if (isNaN(x)) return 'NaN';
    if (!isFinite(x)) return x > 0 ? 'Inf' : '-Inf';
    return Number(x.toPrecision(5)).toString();
  }
  // |t - r| as metrics::value_error has it: a non-finite pair that differs is infinite.
  function valueError(t, r) {
    if (isFinite(t) && isFinite(r)) return Math.abs(Math.fround(t - r));
    return (isNaN(t) && isNaN(r)) || t === r ? 0 : Infinity;
  }

  function Viewer(root) {
    var cfg = JSON.parse(root.querySelector('.viewer-config').textContent);
    var items = cfg.items, W = cfg.width, H = cfg.height;
    var canvas = root.querySelector('.viewer-canvas'), ctx = canvas.getContext('2d');
    var split = root.querySelector('.viewer-split'), splitOn = root.querySelector('.viewer-split-on');
    var bSelect = root.querySelector('.viewer-b'), evInput = root.querySelector('.viewer-ev');
    var readout = root.querySelector('.viewer-readout');
    var st = {a: items.length > 1 && cfg.reference === 0 ? 1 : 0, b: Math.max(cfg.reference, 0),
              mode: 'shaded', ev: 0, split: false, fit: 1, scale: 1, ox: 0, oy: 0, cursor: null};
    var cache = {};
    bSelect.value = String(st.b);

    function ref() { return cfg.reference >= 0 ? items[cfg.reference] : null; }
    function ensure(item) {
      var need = [item.data];
      if (ref() && ref().data) need.push(ref().data);
      need.forEach(function (src) { if (src) loadData(src, draw); });
    }
    function ready() {
      var pending = false;
      [st.a, st.b].forEach(function (i) {
        [items[i].data, ref() ? ref().data : ''].forEach(function (src) {
          if (src && !data[src] && !failed[src]) pending = true;
        });
      });
      return !pending;
    }
    // V (grey, or RGB from its first three channels) or the error, drawn from
    // the data at the exposure; null when the data are missing. One drawing
    // per item and mode is kept, at the last exposure asked for (a drawing per
    // exposure would pile up 8 MB canvases at 1080p as the slider moves).
    function computed(i, mode) {
      var item = items[i], key = i + ':' + mode;
      if (cache[key] && cache[key].ev === st.ev) return cache[key].canvas;
      var d = data[item.data], r = ref() ? data[ref().data] : null;
      if (!d) return null;
      var isRef = i === cfg.reference, gain = Math.pow(2, st.ev), n = d.width * d.height;
      if (mode === 'error' && !isRef && !r) return null;
      if (mode === 'error' && isRef && !d.sigma) return null;
      var c = document.createElement('canvas');
      c.width = d.width; c.height = d.height;
      var cx = c.getContext('2d'), img = cx.createImageData(d.width, d.height), px = img.data;
      var nc = d.channels, fs = cfg.full_scale > 0 ? cfg.full_scale : 1;
      for (var p = 0; p < n; ++p) {
        var o = 4 * p;
        px[o + 3] = 255;
        if (mode === 'v') {
          for (var k = 0; k < 3; ++k) {
            var v = d.v[p * nc + (nc >= 3 ? k : 0)];
            if (isNaN(v)) { px[o] = 255; px[o + 1] = 0; px[o + 2] = 255; break; }
            px[o + k] = Math.round(Math.min(Math.max(v * gain, 0), 1) * 255);
          }
        } else {
          var e = 0;
          if (isRef) e = d.sigma[p * d.sigmaChannels];
          else if (!r.measured || r.measured[p])  // error.png shows none where none is measured
            for (var q = 0; q < nc; ++q) e = Math.max(e, valueError(d.v[p * nc + q], r.v[p * nc + q]));
          var t = e * gain / fs;
          t = isNaN(t) || t > 1 ? 1 : t;
          var l = 3 * Math.round(t * 255);
          px[o] = cfg.lut[l]; px[o + 1] = cfg.lut[l + 1]; px[o + 2] = cfg.lut[l + 2];
        }
      }
      cx.putImageData(img, 0, 0);
      cache[key] = {ev: st.ev, canvas: c};
      return c;
    }
    // What item i shows in the current mode: a drawable, or a note why not.
    function source(i) {
      var item = items[i], m = st.mode;
      if (m === 'shaded' || m === 'flip') {
        var src = m === 'shaded' ? item.shaded : item.flip;
        if (!src) return {note: 'no ' + (m === 'flip' ? 'FLIP map' : 'shaded image')};
        var e = image(src, draw);
        return e.ok ? {img: e.img} : {note: e.bad ? 'missing ' + src : 'loading\u2026'};
      }
      if (!item.data) return {note: 'no V data (run without images, or report --no-viewer-data)'};
      if (!data[item.data] || (m === 'error' && ref() && ref().data && !data[ref().data] &&
                               !failed[ref().data])) {
        ensure(item);
        return {note: failed[item.data] ? 'missing ' + item.data : 'loading\u2026'};
      }
      var c = computed(i, m);
      return c ? {img: c} : {note: 'no reference V to compare with'};
    }

    function resize() {
      var avail = Math.max(root.clientWidth - 22, 160);
      // Whole screen pixels per image pixel when the image fits at 1:1 or
      // more, so that nearest-neighbour drawing keeps every pixel's size.
      var fit = Math.min(avail / W, 720 / H);
      if (fit >= 1) fit = Math.floor(fit);
      var w = Math.max(1, Math.round(W * fit)), h = Math.max(1, Math.round(H * fit));
      if (canvas.width !== w || canvas.height !== h) {
        canvas.width = w; canvas.height = h;
        // The stage and the split slider as wide as the canvas, so that the
        // slider's thumb sits on the split line.
        root.querySelector('.viewer-stage').style.width = w + 'px';
        split.style.width = w + 'px';
        st.scale = st.fit = fit; st.ox = st.oy = 0;
      }
    }
    function clampView() {
      var vw = canvas.width / st.scale, vh = canvas.height / st.scale;
      st.ox = Math.min(Math.max(st.ox, 0), Math.max(W - vw, 0));
      st.oy = Math.min(Math.max(st.oy, 0), Math.max(H - vh, 0));
    }
    function zoomAt(px, py, factor) {
      var ix = st.ox + px / st.scale, iy = st.oy + py / st.scale;
      st.scale = Math.min(Math.max(st.scale * factor, st.fit), Math.max(64, 32 * st.fit));
      st.ox = ix - px / st.scale; st.oy = iy - py / st.scale;
      clampView();
      draw();
    }
    function paint(i, x0, x1) {
      var s = source(i);
      ctx.save();
      ctx.beginPath(); ctx.rect(x0, 0, x1 - x0, canvas.height); ctx.clip();
      ctx.fillStyle = '#2a2f3a'; ctx.fillRect(x0, 0, x1 - x0, canvas.height);
      if (s.img) {
        ctx.imageSmoothingEnabled = st.scale < 1;  // filtered when shrunk, blocks when enlarged
        ctx.setTransform(st.scale, 0, 0, st.scale, -st.ox * st.scale, -st.oy * st.scale);
        ctx.drawImage(s.img, 0, 0, W, H);
      } else {
        ctx.fillStyle = '#c8d0de'; ctx.font = '13px sans-serif';
        ctx.fillText(s.note, x0 + 10, canvas.height / 2);
      }
      ctx.restore();
    }
    function label(text, x, right) {
      ctx.font = '12px ui-monospace, monospace';
      var w = ctx.measureText(text).width + 10;
      ctx.fillStyle = 'rgba(20,24,32,0.75)';
      ctx.fillRect(right ? x - w : x, 0, w, 18);
      ctx.fillStyle = '#fff';
      ctx.fillText(text, (right ? x - w : x) + 5, 13);
    }
    function splitX() { return Math.round(canvas.width * split.value / 1000); }
    function draw() {
      resize();
      var cw = canvas.width, sx = st.split ? splitX() : cw;
      paint(st.a, 0, sx);
      if (st.split) {
        paint(st.b, sx, cw);
        ctx.fillStyle = '#d0342c'; ctx.fillRect(sx - 1, 0, 2, canvas.height);
        label(items[st.b].label, cw, true);
      }
      label(items[st.a].label, 0, false);
      root.querySelectorAll('.viewer-items button').forEach(function (b) {
        var i = Number(b.dataset.item);
        b.setAttribute('aria-pressed', String(i === st.a));
        b.classList.toggle('b-side', st.split && i === st.b);
      });
      root.querySelectorAll('.viewer-modes button').forEach(function (b) {
        b.setAttribute('aria-pressed', String(b.dataset.mode === st.mode));
      });
      root.querySelector('.viewer-zoom').textContent =
          st.scale === st.fit ? 'fit' : (st.scale / st.fit * 100).toFixed(0) + '% (' +
          st.scale.toFixed(st.scale < 10 ? 2 : 0) + ' px/pixel)';
      split.hidden = !st.split;
      splitOn.checked = st.split;
      root.dataset.item = String(st.a);
      root.dataset.mode = st.mode;
      root.dataset.scale = String(st.scale);
      root.dataset.fit = String(st.fit);
      root.dataset.offset = st.ox + ',' + st.oy;
      showReadout();
      root.dataset.state = ready() ? 'ready' : 'loading';
    }
    // The pixel under the cursor and its values, as text and as data-*
    // attributes in full precision (for scripts).
    function showReadout() {
      var c = st.cursor;
      if (!c) return;
      var x = Math.floor(st.ox + c.x / st.scale), y = Math.floor(st.oy + c.y / st.scale);
      var i = st.split && c.x >= splitX() ? st.b : st.a, item = items[i];
      var ds = readout.dataset;
      ['v', 'vref', 'error', 'sigma', 'measured'].forEach(function (k) { delete ds[k]; });
      if (x < 0 || y < 0 || x >= W || y >= H) { readout.textContent = 'outside the image'; return; }
      ds.x = String(x); ds.y = String(y); ds.item = String(i);
      var d = data[item.data], r = ref() ? data[ref().data] : null;
      var text = item.label + ' (' + x + ', ' + y + ')';
      function values(arr, channels) {
        var out = [];
        for (var k = 0; k < channels; ++k) out.push(arr[(y * W + x) * channels + k]);
        return out;
      }
      if (d) {
        var v = values(d.v, d.channels);
        ds.v = v.join(' ');
        text += '  V ' + v.map(fmt).join(' ');
      } else {
        text += '  V ' + (item.data ? 'loading\u2026' : 'not available');
      }
      if (r) {
        var rv = values(r.v, r.channels);
        ds.vref = rv.join(' ');
        text += '  V_ref ' + rv.map(fmt).join(' ');
        if (d && d.channels === r.channels && i !== cfg.reference) {
          var e = 0;
          for (var k = 0; k < v.length; ++k) e = Math.max(e, valueError(v[k], rv[k]));
          ds.error = String(e);
          text += '  |error| ' + fmt(e);
          if (r.measured && !r.measured[y * W + x]) {
            ds.measured = 'false';
            text += ' (not measured)';
          }
        }
        if (r.sigma) {
          var s = values(r.sigma, r.sigmaChannels);
          ds.sigma = s.join(' ');
          text += '  \u03c3 ' + s.map(fmt).join(' ');
        }
      }
      readout.textContent = text;
    }
    function cursorAt(e) {
      var rect = canvas.getBoundingClientRect();
      return {x: (e.clientX - rect.left) * canvas.width / rect.width,
              y: (e.clientY - rect.top) * canvas.height / rect.height};
    }
    function show(i) {
      st.a = (i + items.length) % items.length;
      ensure(items[st.a]);
      draw();
    }
    function setMode(m) { st.mode = m; ensure(items[st.a]); ensure(items[st.b]); draw(); }
    function setEv(ev) {
      st.ev = Math.min(Math.max(ev, -8), 8);
      evInput.value = String(st.ev);
      root.querySelector('.viewer-ev-out').textContent = (st.ev >= 0 ? '+' : '') + st.ev + ' EV';
      draw();
    }

    root.querySelectorAll('.viewer-items button').forEach(function (b) {
      b.addEventListener('click', function () { show(Number(b.dataset.item)); });
    });
    root.querySelectorAll('.viewer-modes button').forEach(function (b) {
      b.addEventListener('click', function () { setMode(b.dataset.mode); });
    });
    evInput.addEventListener('input', function () { setEv(Number(evInput.value)); });
    splitOn.addEventListener('change', function () { st.split = splitOn.checked; draw(); });
    bSelect.addEventListener('change', function () { st.b = Number(bSelect.value); ensure(items[st.b]); draw(); });
    split.addEventListener('input', draw);
    root.querySelector('.viewer-fit').addEventListener('click', function () {
      st.scale = st.fit; st.ox = st.oy = 0; draw();
    });
    canvas.addEventListener('wheel', function (e) {
      e.preventDefault();
      var c = cursorAt(e);
      zoomAt(c.x, c.y, e.deltaY < 0 ? 2 : 0.5);
    }, {passive: false});
    var drag = null;
    canvas.addEventListener('mousedown', function (e) {
      root.focus();
      drag = {x: e.clientX, y: e.clientY, ox: st.ox, oy: st.oy};
    });
    window.addEventListener('mouseup', function () { drag = null; });
    canvas.addEventListener('mousemove', function (e) {
      st.cursor = cursorAt(e);
      if (drag && e.buttons) {
        st.ox = drag.ox - (e.clientX - drag.x) / st.scale;
        st.oy = drag.oy - (e.clientY - drag.y) / st.scale;
        clampView();
        draw();
      } else {
        showReadout();
      }
    });
    canvas.addEventListener('mouseleave', function () { st.cursor = null; });
    root.addEventListener('keydown', function (e) {
      if (e.ctrlKey || e.metaKey || e.altKey) return;
      if (e.target.tagName === 'SELECT' || e.target.tagName === 'INPUT') return;
      var k = e.key, c = st.cursor || {x: canvas.width / 2, y: canvas.height / 2};
      if (k >= '1' && k <= '9') { if (Number(k) <= items.length) show(Number(k) - 1); }
      else if (k === 'ArrowRight') show(st.a + 1);
      else if (k === 'ArrowLeft') show(st.a - 1);
      else if (k === 's') setMode('shaded');
      else if (k === 'v') setMode('v');
      else if (k === 'e') setMode('error');
      else if (k === 'f') setMode('flip');
      else if (k === 'c') { st.split = !st.split; ensure(items[st.b]); draw(); }
      else if (k === 'b') { st.b = st.a; bSelect.value = String(st.b); draw(); }
      else if (k === '[') setEv(st.ev - 0.5);
      else if (k === ']') setEv(st.ev + 0.5);
      else if (k === '+' || k === '=') zoomAt(c.x, c.y, 2);
      else if (k === '-') zoomAt(c.x, c.y, 0.5);
      else if (k === '0') { st.scale = st.fit; st.ox = st.oy = 0; draw(); }
      else return;
      e.preventDefault();
    });
    window.addEventListener('resize', draw);
    ensure(items[st.a]);
    draw();
  }
  document.querySelectorAll('section.viewer').forEach(function (root) { Viewer(root); });
})();
)js";

}  // namespace

const char* image_viewer_style() { return kViewerStyle; }

const char* image_viewer_script() { return kViewerScript; }

}  // namespace sb::results
