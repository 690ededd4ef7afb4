// The replay of `motus compare`'s report: every engine's kept frames, side by side, in the browser.
//
// index.html has a <section id="replay"> (written by compare/motus/compare/replay.cpp) with one panel
// per engine, in the engines' order, and loads two scripts with <script src>: replay-data.js, which sets
// window.MOTUS_REPLAY (the scene's geometry and every engine's frames), and then this file. A script and
// not JSON to fetch, because a page opened from file:// cannot fetch. Plain canvas, no framework, no
// network. This file is embedded into motus at build time (cmake/embed_text.cmake) and written into
// every report as replay.js.
//
// URL parameters, in the query or in the fragment (index.html?t=1.5, index.html#t=1.5&size=400):
//   t=T     open paused at the frame nearest T seconds of simulated time (the last frame beyond the
//           end, the first before the start), with the replay over the whole window (the
//           "show the whole report" button goes back); without t it plays once when first in view
//   size=N  each panel's canvas N x N CSS pixels (64 to 4096; default 288)
//
// The layout, in CSS pixels (docs/cli.md, "The replay"; tests/test_replay_browser.cpp relies on it):
//   - The section has 16 px of padding left and right and starts with a 40 px title row. With t in the
//     URL the section covers the window, its top left corner at the window's top left corner.
//   - Then the panels, in engine order, left to right, wrapped into rows: with W the section's inner
//     width (the window's width less the 32 px of padding, in the t view), a row holds
//     n = max(1, floor((W + 16) / (N + 16))) panels, 16 px apart, and rows are 16 px apart.
//   - A panel is a 40 px caption (the engine and its version; the time and ΔE/E₀ of the frame shown)
//     above an N x N canvas — or, for an engine that could not run the scene, an N x N box saying why.
//     So panel k's canvas has its top left corner at
//       x = 16 + (k mod n) (N + 16),   y = 40 + floor(k / n) (40 + N + 16) + 40
//     from the section's top left corner.
//   - In the canvas, scene coordinates (x right, y up; a 3-D scene seen along −z, so z is dropped;
//     a 1-D scene on the line y = 0) map by one view for every engine: data.view = [x0, y0, x1, y1]
//     (the walls, or every body over the run of each engine in view: replay.cpp, replay_view and
//     engines_in_view, which leaves out a peer that blew up) is centred and its longer side
//     fills 90 % of the canvas: s = 0.9 N / max(x1 − x0, y1 − y0) (1 m when both are 0), and
//       pixel = (N/2 + (x − (x0 + x1)/2) s,  N/2 − (y − (y0 + y1)/2) s).
//   - The canvas's backing store has devicePixelRatio pixels per CSS pixel, so drawings stay sharp.
//   - Background #f4f6f8 in a 1 px frame of #c8ccd2; walls grey (the solid side lighter); sticks dark
//     grey lines; pins small dark rings; each body a disc of its radius (at least 1 px; a body of
//     radius 0 a dot 3 px in radius) in the colour of its index modulo 8 — the palette of the rendered pictures
//     (render/motus/render/frame.cpp, body_color) — with a rim of that colour at 60 %, at most 2 px
//     wide, where the disc is 3 px or more in radius.
(function () {
  "use strict";

  const PALETTE = [[66, 133, 214], [230, 120, 50], [70, 170, 100], [205, 70, 90],
                   [145, 100, 200], [40, 170, 180], [220, 180, 40], [150, 110, 80]];
  const BACKGROUND = "#f4f6f8", FRAME = "#c8ccd2";
  const WALL_LINE = "#8a8a8a", WALL_FILL = "#e2e4e7", LINE_1D = "#d6d9de";
  const STICK = "#555555", PIN = "#333333";
  const DEFAULT_SIZE = 288;
  const DEPTH_SORT_LIMIT = 3000;  // more bodies than this are drawn colour by colour, without depth order

  const section = document.getElementById("replay");
  if (!section) return;
  // What needs this script is `hidden` in the page (replay.cpp): without JavaScript the section shows
  // only its <noscript> message. The notes first; the panels once there is data, the controls once
  // some engine has frames to play.
  const show = (element) => { if (element) element.hidden = false; };
  const notes = section.querySelector(".replay-notes");
  show(notes);
  const data = window.MOTUS_REPLAY;
  if (!data || !Array.isArray(data.engines)) {
    if (notes) notes.textContent = "The replay's data (replay-data.js) is missing or could not be read.";
    return;
  }

  // ---- The URL: ?t=…&size=… or #t=…&size=… (the fragment wins).
  function parameters() {
    const query = new URLSearchParams(window.location.search);
    const fragment = new URLSearchParams(window.location.hash.replace(/^#/, ""));
    for (const [name, value] of fragment) query.set(name, value);
    return query;
  }
  const params = parameters();
  const sizeParameter = parseInt(params.get("size"), 10);
  const size = Number.isFinite(sizeParameter) ? Math.min(4096, Math.max(64, sizeParameter)) : DEFAULT_SIZE;
  function requestedTime(p) {
    if (!p.has("t") || p.get("t").trim() === "") return null;
    const t = Number(p.get("t"));
    return Number.isFinite(t) ? t : null;
  }

  // ---- The view: one camera for every panel.
  const d = data.dimensions;
  const [vx0, vy0, vx1, vy1] = data.view;
  let extent = Math.max(vx1 - vx0, vy1 - vy0);
  if (!(extent > 0)) extent = 1;
  const scale = 0.9 * size / extent, cx = (vx0 + vx1) / 2, cy = (vy0 + vy1) / 2;
  const px = (x) => size / 2 + (x - cx) * scale;
  const py = (y) => size / 2 - (y - cy) * scale;
  const far = 4 * size / scale + Math.hypot(cx, cy);  // a length that reaches past the canvas, in metres

  // ---- The panels, matched in order to the engines.
  show(section.querySelector(".replay-panels"));
  const panels = [];
  section.querySelectorAll(".replay-panel").forEach((element, k) => {
    element.style.width = size + "px";
    const box = element.querySelector("canvas, .replay-reason");
    if (box) {
      box.style.width = size + "px";
      box.style.height = size + "px";
    }
    const engine = data.engines[k];
    const canvas = element.querySelector("canvas");
    if (!engine || !canvas || !engine.supported || !engine.t.length) return;
    panels.push({
      engine, canvas, ctx: canvas.getContext("2d"), dpr: 1,
      time: element.querySelector(".replay-time"), energy: element.querySelector(".replay-energy"),
    });
  });
  if (!panels.length) return;  // nothing ran: the panels say why, and there is nothing to play
  show(section.querySelector(".replay-controls"));

  // The timeline is the engine with the most frames; every panel shows its own frame nearest in time.
  const master = panels.reduce((a, b) => (b.engine.t.length > a.engine.t.length ? b : a)).engine;
  const times = master.t, last = times.length - 1;
  const spacing = last > 0 ? (times[last] - times[0]) / last : 0;
  const decimals = spacing > 0 ? Math.min(6, Math.max(2, Math.ceil(-Math.log10(spacing) - 1e-9))) : 2;

  function nearest(ts, t) {  // index of the time in the sorted ts nearest to t
    let lo = 0, hi = ts.length - 1;
    if (t <= ts[lo]) return lo;
    if (t >= ts[hi]) return hi;
    while (hi - lo > 1) {
      const mid = (lo + hi) >> 1;
      if (ts[mid] <= t) lo = mid; else hi = mid;
    }
    return t - ts[lo] <= ts[hi] - t ? lo : hi;
  }

  // ---- Drawing.
  function setUpCanvases() {
    const dpr = window.devicePixelRatio || 1;
    for (const p of panels) {
      p.dpr = dpr;
      p.canvas.width = Math.round(size * dpr);
      p.canvas.height = Math.round(size * dpr);
    }
  }

  function rgb(c, f) {
    return "rgb(" + Math.round(c[0] * f) + "," + Math.round(c[1] * f) + "," + Math.round(c[2] * f) + ")";
  }
  const FILLS = PALETTE.map((c) => rgb(c, 1)), RIMS = PALETTE.map((c) => rgb(c, 0.6));

  function drawWalls(ctx) {
    const walls = data.walls;
    ctx.lineWidth = 2;
    ctx.lineCap = "round";
    if (walls.boxes.length) {  // containers: outside is solid
      ctx.fillStyle = WALL_FILL;
      ctx.fillRect(0, 0, size, size);
      ctx.fillStyle = BACKGROUND;
      for (const b of walls.boxes) {
        if (d === 1) ctx.fillRect(px(b[0]), 0, px(b[3]) - px(b[0]), size);
        else ctx.fillRect(px(b[0]), py(b[4]), px(b[3]) - px(b[0]), py(b[1]) - py(b[4]));
      }
      ctx.strokeStyle = WALL_LINE;
      for (const b of walls.boxes) {
        ctx.beginPath();
        if (d === 1) {
          ctx.moveTo(px(b[0]), 0); ctx.lineTo(px(b[0]), size);
          ctx.moveTo(px(b[3]), 0); ctx.lineTo(px(b[3]), size);
        } else {
          ctx.rect(px(b[0]), py(b[4]), px(b[3]) - px(b[0]), py(b[1]) - py(b[4]));
        }
        ctx.stroke();
      }
    }
    for (const p of walls.planes) {  // n·x = offset, free space on the side n points to
      const nx = p[0], ny = d === 1 ? 0 : p[1], length = Math.hypot(nx, ny);
      if (length < 0.5) continue;  // a 3-D plane facing the camera: not drawn
      const ux = nx / length, uy = ny / length, o = p[3] / length;
      const fx = ux * o, fy = uy * o;         // the plane's point nearest the origin
      const tx = -uy * far, ty = ux * far;    // along the plane
      const bx = -ux * far, by = -uy * far;   // into the solid side
      ctx.fillStyle = WALL_FILL;
      ctx.beginPath();
      ctx.moveTo(px(fx - tx), py(fy - ty));
      ctx.lineTo(px(fx + tx), py(fy + ty));
      ctx.lineTo(px(fx + tx + bx), py(fy + ty + by));
      ctx.lineTo(px(fx - tx + bx), py(fy - ty + by));
      ctx.closePath();
      ctx.fill();
      ctx.strokeStyle = WALL_LINE;
      ctx.beginPath();
      ctx.moveTo(px(fx - tx), py(fy - ty));
      ctx.lineTo(px(fx + tx), py(fy + ty));
      ctx.stroke();
    }
    ctx.strokeStyle = WALL_LINE;
    for (const s of walls.segments) {
      ctx.beginPath();
      ctx.moveTo(px(s[0]), py(s[1]));
      ctx.lineTo(px(s[2]), py(s[3]));
      ctx.stroke();
    }
  }

  function drawBodies(ctx, x) {
    const count = data.radius.length;
    const X = (i) => x[i * d], Y = (i) => (d === 1 ? 0 : x[i * d + 1]);
    const radius = (i) => (data.radius[i] > 0 ? Math.max(data.radius[i] * scale, 1) : 3);
    const visible = (i) => X(i) !== null && Y(i) !== null;

    ctx.strokeStyle = STICK;
    ctx.lineWidth = 1.5;
    ctx.beginPath();
    for (const [a, b] of data.sticks) {
      if (!visible(a) || !visible(b)) continue;
      ctx.moveTo(px(X(a)), py(Y(a)));
      ctx.lineTo(px(X(b)), py(Y(b)));
    }
    ctx.stroke();

    const order = [];
    for (let i = 0; i < count; ++i) if (visible(i)) order.push(i);
    if (count <= DEPTH_SORT_LIMIT) {
      if (d === 3) order.sort((a, b) => x[a * 3 + 2] - x[b * 3 + 2]);  // farther (smaller z) first
      for (const i of order) {
        const r = radius(i), c = data.color[i] % PALETTE.length;
        ctx.beginPath();
        ctx.arc(px(X(i)), py(Y(i)), r, 0, 2 * Math.PI);
        ctx.fillStyle = FILLS[c];
        ctx.fill();
        if (r >= 3) {
          ctx.lineWidth = Math.min(2, 0.15 * r);
          ctx.strokeStyle = RIMS[c];
          ctx.beginPath();
          ctx.arc(px(X(i)), py(Y(i)), r - ctx.lineWidth / 2, 0, 2 * Math.PI);
          ctx.stroke();
        }
      }
    } else {  // many bodies: one path per colour
      for (let c = 0; c < PALETTE.length; ++c) {
        ctx.beginPath();
        for (const i of order) {
          if (data.color[i] % PALETTE.length !== c) continue;
          const r = radius(i), X0 = px(X(i)), Y0 = py(Y(i));
          ctx.moveTo(X0 + r, Y0);
          ctx.arc(X0, Y0, r, 0, 2 * Math.PI);
        }
        ctx.fillStyle = FILLS[c];
        ctx.fill();
      }
    }

    ctx.strokeStyle = PIN;
    ctx.lineWidth = 1.5;
    for (const p of data.pins) {
      ctx.beginPath();
      ctx.arc(px(p[0]), py(p[1]), 3, 0, 2 * Math.PI);
      ctx.stroke();
    }
  }

  function signed(v) {
    if (v === null || v === undefined) return "\u2013";  // not finite
    if (v === 0) return "0";
    return (v > 0 ? "+" : "") + v.toExponential(2);
  }

  function drawPanel(p, t) {
    const e = p.engine, f = nearest(e.t, t), ctx = p.ctx;
    ctx.setTransform(p.dpr, 0, 0, p.dpr, 0, 0);
    ctx.fillStyle = BACKGROUND;
    ctx.fillRect(0, 0, size, size);
    drawWalls(ctx);
    if (d === 1) {  // the line the bodies move on
      ctx.strokeStyle = LINE_1D;
      ctx.lineWidth = 1;
      ctx.beginPath();
      ctx.moveTo(0, py(0));
      ctx.lineTo(size, py(0));
      ctx.stroke();
    }
    drawBodies(ctx, e.x[f]);
    ctx.strokeStyle = FRAME;
    ctx.lineWidth = 1;
    ctx.strokeRect(0.5, 0.5, size - 1, size - 1);
    const time = "t = " + e.t[f].toFixed(decimals) + " s";
    const energy = (e.energy_relative ? "\u0394E/E\u2080 = " : "\u0394E = ") + signed(e.energy_error[f]) +
                   (e.energy_relative ? "" : " J (E\u2080 = 0)");
    if (p.time) p.time.textContent = time;
    if (p.energy) p.energy.textContent = energy;
    // (The canvas is role="img": its name is what a screen reader says of the picture.)
    p.canvas.setAttribute("aria-label", e.name + " at " + time + ", " + energy);
  }

  // ---- Playing.
  const slider = section.querySelector(".replay-slider");
  const playButton = section.querySelector(".replay-play");
  const speedSelect = section.querySelector(".replay-speed");
  const clock = section.querySelector(".replay-clock");
  let index = 0, simulated = times[0], playing = false, speed = 1, previous = null;

  function render() {
    const t = times[index];
    for (const p of panels) drawPanel(p, t);
    if (slider) {
      slider.value = String(index);
      slider.setAttribute("aria-valuetext", "t = " + t.toFixed(decimals) + " s");  // (not "frame 12")
    }
    if (clock)
      clock.textContent = "t = " + t.toFixed(decimals) + " s of " + times[last].toFixed(decimals) +
                          " s \u00b7 frame " + (index + 1) + " of " + times.length;
  }
  function seek(i) {
    index = Math.min(last, Math.max(0, i));
    simulated = times[index];
    render();
  }
  function pause() {
    playing = false;
    if (playButton) playButton.textContent = "play";
  }
  function tick(now) {
    if (!playing) return;
    // (at most a quarter of a second at a time: a tab in the background does not jump to the end)
    if (previous !== null) simulated += Math.min(now - previous, 250) / 1000 * speed;
    previous = now;
    let i = index;
    while (i < last && times[i + 1] <= simulated) ++i;
    if (i !== index) {
      index = i;
      render();
    }
    if (index >= last) pause();
    else window.requestAnimationFrame(tick);
  }
  function play() {
    if (index >= last) seek(0);
    playing = true;
    previous = null;
    if (playButton) playButton.textContent = "pause";
    window.requestAnimationFrame(tick);
  }
  function toggle() { if (playing) pause(); else play(); }
  function step(by) {
    pause();
    seek(index + by);
  }

  if (slider) {
    slider.max = String(last);
    slider.addEventListener("input", () => {
      pause();
      seek(Number(slider.value));
    });
  }
  if (playButton) playButton.addEventListener("click", toggle);
  const back = section.querySelector(".replay-back"), forward = section.querySelector(".replay-forward");
  if (back) back.addEventListener("click", () => step(-1));
  if (forward) forward.addEventListener("click", () => step(1));
  if (speedSelect) {
    speed = Number(speedSelect.value) || 1;
    speedSelect.addEventListener("change", () => { speed = Number(speedSelect.value) || 1; });
  }

  // Keys: space plays or pauses, ← and → step a frame — only while the focus is in the replay (the
  // section itself, which a click in it focuses, or one of its controls), so that elsewhere space
  // scrolls the page as always; and not when a control has the focus and does its own thing with the
  // key (a button's space, the slider's arrows).
  section.addEventListener("keydown", (event) => {
    if (event.defaultPrevented || event.altKey || event.ctrlKey || event.metaKey) return;
    const target = event.target, tag = target && target.tagName;
    if (tag === "INPUT" || tag === "SELECT" || tag === "TEXTAREA" || tag === "VIDEO" || (target && target.isContentEditable))
      return;
    if (tag === "BUTTON" && (event.key === " " || event.key === "Enter")) return;
    if (event.key === " ") toggle();
    else if (event.key === "ArrowLeft") step(-1);
    else if (event.key === "ArrowRight") step(1);
    else return;
    event.preventDefault();
  });

  // ?t= (or #t=): the replay over the whole window, paused at that instant.
  const closeButton = section.querySelector(".replay-close");
  function openAt(t) {
    section.classList.add("replay-theatre");
    document.documentElement.style.overflow = "hidden";
    if (closeButton) closeButton.hidden = false;
    pause();
    seek(nearest(times, t));
  }
  if (closeButton)
    closeButton.addEventListener("click", () => {
      section.classList.remove("replay-theatre");
      document.documentElement.style.overflow = "";
      closeButton.hidden = true;
      section.scrollIntoView();
    });
  window.addEventListener("hashchange", () => {
    const t = requestedTime(parameters());
    if (t !== null) openAt(t);
  });
  let ratio = window.devicePixelRatio || 1;
  window.addEventListener("resize", () => {  // a zoom changes the device pixel ratio
    if ((window.devicePixelRatio || 1) === ratio) return;
    ratio = window.devicePixelRatio || 1;
    setUpCanvases();
    render();
  });

  setUpCanvases();
  const start = requestedTime(params);
  if (start !== null) {
    openAt(start);
  } else {
    // Otherwise the first frame, and one play-through when the replay first comes into view.
    seek(0);
    const still = window.matchMedia && window.matchMedia("(prefers-reduced-motion: reduce)").matches;
    if (!still && last > 0) {
      if ("IntersectionObserver" in window) {
        const observer = new IntersectionObserver((entries) => {
          if (!entries.some((entry) => entry.isIntersecting)) return;
          observer.disconnect();
          play();
        });
        observer.observe(section);
      } else {
        play();
      }
    }
  }
})();
