/* vorball results page: draws the data of the JSON script element #vb-data with NGL.
 * Frames: the slider moves the atoms (updatePosition) and redraws the
 * frame's paths, points, figures, profiles and colours; the measure selector
 * picks the per-atom measure that colours the atoms. When the page has
 * drawn frame k, body's data-ready is "k+1" and data-paths, data-atoms,
 * data-drawn-points, data-measure and data-facts say what it drew (the
 * page tests read them). */
(function () {
  "use strict";
  var data = JSON.parse(document.getElementById("vb-data").textContent);
  var body = document.body;
  var stage = null, comp = null, shapeComp = null, scheme = null, current = 0;

  /* HOLE's colours for a pore radius: too narrow for a water molecule
   * (red), room for one (green), wider (blue). */
  var NARROW = 1.15, WIDE = 2.30;
  function radiusColor(r) {
    if (r < NARROW) return [0.85, 0.1, 0.1];
    if (r < WIDE) return [0.1, 0.65, 0.2];
    return [0.15, 0.3, 0.85];
  }

  /* Blue (low) - white - red (high) over [lo, hi]; grey for no value. */
  function valueColor(v, lo, hi) {
    if (v === null || v === undefined) return 0x999999;
    var t = hi > lo ? (v - lo) / (hi - lo) : 0.5;
    t = Math.max(0, Math.min(1, t));
    var r, g, b;
    if (t < 0.5) { r = 2 * t; g = 2 * t; b = 1; } else { r = 1; g = 2 - 2 * t; b = 2 - 2 * t; }
    return (Math.round(r * 255) << 16) | (Math.round(g * 255) << 8) | Math.round(b * 255);
  }

  function text(el, s) { el.textContent = s; }

  function showFacts(fr) {
    var table = document.getElementById("facts");
    table.innerHTML = "";
    fr.facts.forEach(function (kv) {
      var tr = document.createElement("tr");
      var k = document.createElement("td"), v = document.createElement("td");
      text(k, kv[0]); text(v, kv[1]); v.className = "v";
      tr.appendChild(k); tr.appendChild(v); table.appendChild(tr);
    });
    body.dataset.facts = JSON.stringify(fr.facts);
  }

  function showLegend(fr) {
    var lg = document.getElementById("legend");
    lg.innerHTML = "";
    function item(rgb, label) {
      var s = document.createElement("span");
      s.style.background = rgb;
      lg.appendChild(s);
      lg.appendChild(document.createTextNode(" " + label + "  "));
    }
    if (fr.paths.length) {
      item("rgb(217,26,26)", "radius < " + NARROW + " Å");
      item("rgb(26,166,51)", NARROW + "–" + WIDE + " Å");
      item("rgb(38,77,217)", "> " + WIDE + " Å");
    }
    var m = measureOf(fr);
    if (m) {
      var r = range(m.v);
      lg.appendChild(document.createElement("br"));
      item("#" + valueColor(r[0], r[0], r[1]).toString(16).padStart(6, "0"), m.name + " " + r[0]);
      item("#" + valueColor(r[1], r[0], r[1]).toString(16).padStart(6, "0"), r[1].toString());
    }
    if (fr.points.length) {
      lg.appendChild(document.createElement("br"));
      fr.points.forEach(function (pt, k) { item(POINT_COLORS_CSS[k % POINT_COLORS_CSS.length], pt.name); });
    }
  }

  /* The measure the selector names (by name, so that frames may list
   * theirs in any order), or the frame's first; null without any. */
  function measureOf(fr) {
    if (!fr.measures.length) return null;
    var sel = document.getElementById("measure");
    var name = sel && sel.value;
    for (var i = 0; i < fr.measures.length; i++) if (fr.measures[i].name === name) return fr.measures[i];
    return fr.measures[0];
  }

  var POINT_COLORS = [[1.0, 0.55, 0.0], [0.55, 0.2, 0.7], [0.0, 0.6, 0.6]];
  var POINT_COLORS_CSS = ["rgb(255,140,0)", "rgb(140,51,179)", "rgb(0,153,153)"];

  function range(v) {
    var lo = Infinity, hi = -Infinity;
    v.forEach(function (x) { if (x !== null) { lo = Math.min(lo, x); hi = Math.max(hi, x); } });
    return lo <= hi ? [lo, hi] : [0, 0];
  }

  function showProfiles(fr) {
    var svg = document.getElementById("profile");
    var NS = "http://www.w3.org/2000/svg";
    svg.innerHTML = "";
    if (!fr.profiles.length) return;
    var s0 = Infinity, s1 = -Infinity, r1 = 0;
    fr.profiles.forEach(function (p) {
      p.s.forEach(function (s) { s0 = Math.min(s0, s); s1 = Math.max(s1, s); });
      p.r.forEach(function (r) { if (r !== null) r1 = Math.max(r1, r); });
    });
    if (!(s1 > s0)) s1 = s0 + 1;
    r1 = Math.max(r1, WIDE) * 1.05;
    var X = function (s) { return 40 + 310 * (s - s0) / (s1 - s0); };
    var Y = function (r) { return 200 - 185 * r / r1; };
    function line(x0, y0, x1, y1, color) {
      var l = document.createElementNS(NS, "line");
      l.setAttribute("x1", x0); l.setAttribute("y1", y0);
      l.setAttribute("x2", x1); l.setAttribute("y2", y1);
      l.setAttribute("stroke", color); svg.appendChild(l);
    }
    function label(x, y, s, anchor) {
      var t = document.createElementNS(NS, "text");
      t.setAttribute("x", x); t.setAttribute("y", y);
      t.setAttribute("text-anchor", anchor || "middle");
      t.textContent = s; svg.appendChild(t);
    }
    line(40, 200, 350, 200, "#444"); line(40, 15, 40, 200, "#444");
    line(40, Y(NARROW), 350, Y(NARROW), "#e8b0b0");
    label(195, 216, "axial coordinate (Å)");
    label(36, 203, "0", "end"); label(36, Y(r1 / 1.05) + 3, (r1 / 1.05).toFixed(2), "end");
    label(40, 212, s0.toFixed(1)); label(350, 212, s1.toFixed(1));
    var colors = ["#1f3b57", "#c0392b", "#27ae60", "#8e44ad", "#d35400"];
    fr.profiles.forEach(function (p, k) {
      var pts = [];
      for (var i = 0; i < p.s.length; i++) if (p.r[i] !== null) pts.push(X(p.s[i]).toFixed(1) + "," + Y(p.r[i]).toFixed(1));
      var pl = document.createElementNS(NS, "polyline");
      pl.setAttribute("points", pts.join(" "));
      pl.setAttribute("fill", "none");
      pl.setAttribute("stroke", colors[k % colors.length]);
      pl.setAttribute("stroke-width", "1.5");
      var title = document.createElementNS(NS, "title");
      title.textContent = p.name; pl.appendChild(title);
      svg.appendChild(pl);
    });
    label(345, 12, "radius (Å) — " + fr.profiles.map(function (p) { return p.name; }).join(", "), "end");
  }

  /* The frame's paths (tubes coloured by radius) and point sets (small
   * markers); returns [paths drawn, points drawn]. */
  function drawShapes(fr) {
    if (shapeComp) { stage.removeComponent(shapeComp); shapeComp = null; }
    var n = 0, np = 0;
    if (!fr.paths.length && !fr.points.length) return [0, 0];
    var shape = new NGL.Shape("paths");
    fr.paths.forEach(function (p) {
      for (var i = 0; i < p.r.length; i++) {
        var c = [p.xyz[3 * i], p.xyz[3 * i + 1], p.xyz[3 * i + 2]];
        var r = p.r[i] === null ? 0.2 : p.r[i];
        shape.addSphere(c, radiusColor(r), Math.max(0.15, Math.min(r, 0.6)), p.name + " r=" + r);
        if (i > 0) {
          var b = [p.xyz[3 * i - 3], p.xyz[3 * i - 2], p.xyz[3 * i - 1]];
          shape.addCylinder(b, c, radiusColor(r), 0.12, p.name);
        }
      }
      n++;
    });
    fr.points.forEach(function (pt, k) {
      var color = POINT_COLORS[k % POINT_COLORS.length];
      for (var i = 0; i < pt.r.length; i++) {
        var c = [pt.xyz[3 * i], pt.xyz[3 * i + 1], pt.xyz[3 * i + 2]];
        shape.addSphere(c, color, 0.3, pt.name + " " + (i + 1) + (pt.r[i] === null ? "" : " r=" + pt.r[i]));
        np++;
      }
    });
    shapeComp = stage.addComponentFromObject(shape);
    shapeComp.addRepresentation("buffer");
    return [n, np];
  }

  function colourAtoms(fr) {
    var m = measureOf(fr);
    if (!m) return "element";
    var v = m.v, r = range(v);
    /* NGL 2 spells it ColormakerRegistry, the embedded 0.8 ColorMakerRegistry. */
    var registry = NGL.ColormakerRegistry || NGL.ColorMakerRegistry;
    return registry.addScheme(function () {
      this.atomColor = function (atom) { return valueColor(v[atom.index], r[0], r[1]); };
    }, "vorball-values");
  }

  function showFrame(k) {
    var fr = data.frames[k];
    text(document.getElementById("frame-label"), fr.label + " (" + (k + 1) + " of " + data.frames.length + ")");
    showFacts(fr);
    showLegend(fr);
    showProfiles(fr);
    var drawn = [0, 0];
    current = k;
    if (stage && comp) {
      var xyz = fr.xyz;
      if (xyz) {
        comp.structure.updatePosition(new Float32Array(xyz));
        comp.updateRepresentations({ position: true });
      }
      scheme = colourAtoms(fr);
      comp.reprList.forEach(function (r) { r.setColor(scheme); });
      drawn = drawShapes(fr);
      stage.viewer.requestRender();
    }
    var m = measureOf(fr);
    body.dataset.measure = m ? m.name : "";
    body.dataset.paths = String(fr.paths.length);
    body.dataset.drawnPaths = String(drawn[0]);
    body.dataset.drawnPoints = String(drawn[1]);
    body.dataset.ready = String(k + 1);
  }

  function setupSlider() {
    if (data.frames.length < 2) return;
    var box = document.getElementById("frames"), input = document.getElementById("frame");
    box.className = "shown";
    input.max = String(data.frames.length - 1);
    input.addEventListener("input", function () { showFrame(Number(input.value)); });
  }

  /* The measure selector: the names of every frame's measures, shown when
   * there is one at least; choosing one recolours the frame shown. */
  function setupMeasures() {
    var names = [];
    data.frames.forEach(function (f) {
      f.measures.forEach(function (m) { if (names.indexOf(m.name) < 0) names.push(m.name); });
    });
    body.dataset.measures = JSON.stringify(names);
    if (!names.length) return;
    var box = document.getElementById("measures"), sel = document.getElementById("measure");
    box.className = "shown";
    names.forEach(function (name) {
      var o = document.createElement("option");
      o.value = name; o.textContent = name; sel.appendChild(o);
    });
    sel.addEventListener("change", function () { showFrame(current); });
  }

  function start() {
    setupSlider();
    setupMeasures();
    if (data.frames.some(function (f) { return f.profiles.length > 0; }))
      document.getElementById("profiles").className = "shown";
    body.dataset.atoms = String(data.atoms);
    try {
      stage = new NGL.Stage("viewer", { backgroundColor: "white" });
    } catch (e) {
      stage = null;
      text(document.getElementById("error"), "The 3D view needs WebGL: " + e.message);
      showFrame(0);
      return;
    }
    window.addEventListener("resize", function () { stage.handleResize(); });
    var blob = new Blob([data.pdb], { type: "text/plain" });
    stage.loadFile(blob, { ext: "pdb", name: data.source }).then(function (c) {
      comp = c;
      var few = data.atoms <= 20000;
      var fr0 = data.frames[0];
      scheme = colourAtoms(fr0);
      var hasPaths = data.frames.some(function (f) { return f.paths.length > 0 || f.points.length > 0; });
      if (few) {
        comp.addRepresentation("spacefill", {
          radiusType: "bfactor", radiusScale: 1.0, color: scheme,
          opacity: hasPaths ? 0.25 : 1.0, depthWrite: !hasPaths
        });
      } else {
        comp.addRepresentation("line", { color: scheme });
      }
      /* "chainindex": a scheme of NGL 0.8 (embedded) and of NGL 2 alike. */
      if (data.annotated) comp.addRepresentation("cartoon", { color: "chainindex", opacity: hasPaths ? 0.5 : 1.0 });
      body.dataset.viewAtoms = String(comp.structure.atomCount);
      showFrame(0);
      /* The view fits the molecule, not the shapes: a vertex of a cell on
       * the hull can lie far out. NGL 2 calls it autoView, 0.8 centerView. */
      if (comp.autoView) comp.autoView(); else comp.centerView(true);
    }).catch(function (e) {
      text(document.getElementById("error"), "The viewer could not load the molecule: " + e);
      showFrame(0);
    });
  }

  start();
})();
