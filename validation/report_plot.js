// Zoomable pressure overlays of report.html: inline SVG, no library, no network.
// Each <figure class="vb-zoom"> holds a <script type="application/json"> with
// {title, xlabel, panels: [{ylabel, series: [{name, x, y, exact}], zero}]}.
// Drag across a panel to zoom into that x range (the y ranges fit the visible points);
// double-click or "reset" to see everything again; click a legend entry to hide a series.
// Tick steps are 1, 2 or 5 times a power of ten, and a step is widened until the labels
// it needs fit side by side, so tick labels never overlap. A drawn figure gets
// data-rendered="1" (the browser test reads it).
(function () {
  "use strict";
  var NS = "http://www.w3.org/2000/svg";
  var COLOURS = ["#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"];
  var CHAR = 6.6; // px per character of an 11 px label (digits, sign, point)
  var W = 860, LEFT = 72, RIGHT = 16, TOP = 26, GAP = 10, BOTTOM = 42, HEIGHTS = [250, 150];

  function el(tag, attrs, parent) {
    var e = document.createElementNS(NS, tag);
    for (var k in attrs) { e.setAttribute(k, attrs[k]); }
    if (parent) { parent.appendChild(e); }
    return e;
  }

  function text(parent, x, y, s, attrs) {
    var t = el("text", attrs || {}, parent);
    t.setAttribute("x", x);
    t.setAttribute("y", y);
    t.textContent = s;
    return t;
  }

  function niceStep(span, count) {
    var raw = span / Math.max(count, 1);
    var p = Math.pow(10, Math.floor(Math.log10(raw)));
    var m = raw / p;
    return (m <= 1 ? 1 : m <= 2 ? 2 : m <= 5 ? 5 : 10) * p;
  }

  function label(v, step) {
    var decimals = Math.max(0, -Math.floor(Math.log10(step) + 1e-9));
    var s = v.toFixed(Math.min(decimals, 12));
    return s === "-0" || /^-0\.0*$/.test(s) ? s.slice(1) : s;
  }

  // ticks over [lo, hi] on an axis of `pixels`; `room(labels)` is the pixels one label needs
  function ticks(lo, hi, pixels, room, spacing) {
    var count = Math.max(2, Math.floor(pixels / spacing));
    for (;;) {
      var step = niceStep(hi - lo, count), values = [], labels = [];
      for (var v = Math.ceil(lo / step) * step; v <= hi + step * 1e-9; v += step) {
        var r = Math.abs(v) < step * 1e-9 ? 0 : v;
        values.push(r);
        labels.push(label(r, step));
      }
      var apart = values.length > 1 ? pixels * step / (hi - lo) : pixels;
      if (apart >= room(labels) + 8 || count <= 2) { return {values: values, labels: labels}; }
      count -= 1;
    }
  }

  function extent(series, x0, x1) {
    var lo = Infinity, hi = -Infinity;
    series.forEach(function (s) {
      if (s.hidden) { return; }
      for (var i = 0; i < s.x.length; i++) {
        var y = s.y[i];
        if (s.x[i] >= x0 && s.x[i] <= x1 && y !== null) { lo = Math.min(lo, y); hi = Math.max(hi, y); }
      }
    });
    if (!isFinite(lo)) { lo = 0; hi = 1; }
    if (hi - lo < 1e-12 * Math.max(1, Math.abs(hi))) { lo -= 0.5; hi += 0.5; }
    var pad = 0.05 * (hi - lo);
    return [lo - pad, hi + pad];
  }

  function draw(figure, spec, state) {
    var svg = figure.querySelector("svg");
    while (svg.firstChild) { svg.removeChild(svg.firstChild); }
    var inner = W - LEFT - RIGHT, top = TOP;
    text(svg, LEFT, 16, spec.title, {"class": "vb-title"});
    spec.panels.forEach(function (panel, k) {
      var h = HEIGHTS[k] || 150, yr = extent(panel.series, state.x0, state.x1);
      var sx = function (x) { return LEFT + (x - state.x0) / (state.x1 - state.x0) * inner; };
      var sy = function (y) { return top + h - (y - yr[0]) / (yr[1] - yr[0]) * h; };
      var id = figure.id + "-clip" + k;
      el("rect", {x: LEFT, y: top, width: inner, height: h, id: id + "r"}, el("clipPath", {id: id}, svg));
      el("rect", {x: LEFT, y: top, width: inner, height: h, "class": "vb-frame"}, svg);
      var yt = ticks(yr[0], yr[1], h, function () { return 11; }, 36);
      yt.values.forEach(function (v, i) {
        el("line", {x1: LEFT, x2: LEFT + inner, y1: sy(v), y2: sy(v), "class": "vb-grid"}, svg);
        text(svg, LEFT - 6, sy(v) + 4, yt.labels[i], {"class": "vb-tick vb-y", "text-anchor": "end"});
      });
      var xt = ticks(state.x0, state.x1, inner, function (labels) {
        return CHAR * Math.max.apply(null, labels.map(function (s) { return s.length; }));
      }, 70);
      xt.values.forEach(function (v, i) {
        el("line", {x1: sx(v), x2: sx(v), y1: top, y2: top + h, "class": "vb-grid"}, svg);
        if (k === spec.panels.length - 1) {
          text(svg, sx(v), top + h + 15, xt.labels[i], {"class": "vb-tick vb-x", "text-anchor": "middle"});
        }
      });
      if (panel.zero && yr[0] < 0 && yr[1] > 0) {
        el("line", {x1: LEFT, x2: LEFT + inner, y1: sy(0), y2: sy(0), "class": "vb-zero"}, svg);
      }
      text(svg, 16, top + h / 2, panel.ylabel, {"class": "vb-label", transform: "rotate(-90 16 " + (top + h / 2) + ")", "text-anchor": "middle"});
      var g = el("g", {"clip-path": "url(#" + id + ")"}, svg);
      panel.series.forEach(function (s) {
        if (s.hidden) { return; }
        var d = "", dots = "";
        for (var i = 0; i < s.x.length; i++) {
          if (s.y[i] === null) { continue; }
          var px = sx(s.x[i]).toFixed(1), py = sy(s.y[i]).toFixed(1);
          d += (d ? "L" : "M") + px + " " + py;
          dots += "M" + px + " " + py + "h0";
        }
        el("path", {d: d, "class": s.exact ? "vb-exact" : "vb-line", stroke: s.colour}, g);
        if (!s.exact) { el("path", {d: dots, "class": "vb-dots", stroke: s.colour}, g); }
      });
      top += h + GAP;
    });
    text(svg, LEFT + inner / 2, top - GAP + 34, spec.xlabel, {"class": "vb-label", "text-anchor": "middle"});
    var band = el("rect", {x: 0, y: TOP, width: 0, height: top - GAP - TOP, "class": "vb-band", visibility: "hidden"}, svg);
    state.band = band;
    state.bottom = top - GAP;
    figure.setAttribute("data-rendered", "1");
    figure.setAttribute("data-x-range", state.x0 + " " + state.x1);
  }

  function setup(figure, spec, index) {
    figure.id = figure.id || "vb-plot-" + index;
    var all = [];
    spec.panels.forEach(function (p) { all = all.concat(p.series); });
    var names = [];
    all.forEach(function (s) {
      var base = s.name.split(" - ")[0];
      if (names.indexOf(base) < 0) { names.push(base); }
    });
    all.forEach(function (s) {
      var base = s.name.split(" - ")[0];
      s.colour = s.exact ? "#000" : COLOURS[names.indexOf(base) % COLOURS.length];
    });
    var lo = Infinity, hi = -Infinity;
    all.forEach(function (s) { s.x.forEach(function (x) { lo = Math.min(lo, x); hi = Math.max(hi, x); }); });
    if (!(hi > lo)) { hi = lo + 1; }
    var full = {x0: lo, x1: hi}, state = {x0: lo, x1: hi};
    var height = TOP + HEIGHTS.slice(0, spec.panels.length).reduce(function (a, b) { return a + b + GAP; }, 0) + BOTTOM;
    var svg = el("svg", {viewBox: "0 0 " + W + " " + height, width: "100%", role: "img", "aria-label": spec.title});
    figure.insertBefore(svg, figure.firstChild);
    var legend = document.createElement("div");
    legend.className = "vb-legend";
    all.forEach(function (s) {
      var item = document.createElement("span");
      item.className = "vb-key";
      item.innerHTML = "<i style='background:" + s.colour + "'></i>";
      item.appendChild(document.createTextNode(s.name));
      item.addEventListener("click", function () {
        s.hidden = !s.hidden;
        item.classList.toggle("vb-off", s.hidden);
        draw(figure, spec, state);
      });
      legend.appendChild(item);
    });
    var reset = document.createElement("button");
    reset.textContent = "reset zoom";
    reset.addEventListener("click", function () { state.x0 = full.x0; state.x1 = full.x1; draw(figure, spec, state); });
    legend.appendChild(reset);
    svg.parentNode.insertBefore(legend, svg.nextSibling);

    function dataX(evt) {
      var r = svg.getBoundingClientRect(), px = (evt.clientX - r.left) * W / r.width;
      var inner = W - LEFT - RIGHT, f = Math.min(1, Math.max(0, (px - LEFT) / inner));
      return {px: LEFT + f * inner, x: state.x0 + f * (state.x1 - state.x0)};
    }
    var start = null;
    svg.addEventListener("mousedown", function (evt) { start = dataX(evt); evt.preventDefault(); });
    svg.addEventListener("mousemove", function (evt) {
      if (!start) { return; }
      var now = dataX(evt);
      state.band.setAttribute("x", Math.min(start.px, now.px));
      state.band.setAttribute("width", Math.abs(now.px - start.px));
      state.band.setAttribute("visibility", "visible");
    });
    window.addEventListener("mouseup", function (evt) {
      if (!start) { return; }
      var end = dataX(evt), a = Math.min(start.x, end.x), b = Math.max(start.x, end.x);
      var wide = Math.abs(end.px - start.px) > 4;
      start = null;
      if (wide && b > a) { state.x0 = a; state.x1 = b; }
      draw(figure, spec, state);
    });
    svg.addEventListener("dblclick", function () { state.x0 = full.x0; state.x1 = full.x1; draw(figure, spec, state); });
    draw(figure, spec, state);
  }

  function init() {
    var figures = document.querySelectorAll("figure.vb-zoom");
    for (var i = 0; i < figures.length; i++) {
      try {  // one broken figure must not keep the others from drawing
        setup(figures[i], JSON.parse(figures[i].querySelector("script[type='application/json']").textContent), i);
      } catch (err) {
        console.error("viscobem report: plot " + i + " could not be drawn: " + err);
      }
    }
    document.body.setAttribute("data-zoom-ready", String(figures.length));
  }

  if (document.readyState === "loading") { document.addEventListener("DOMContentLoaded", init); } else { init(); }
})();
