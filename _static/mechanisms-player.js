/* The book's player: moves the scenes that the package `mechanisms` exports (mechanisms.present.scene).
 *
 * Each figure is a <div class="mech-player"> holding an SVG still image (one frame, drawn by the package)
 * and the scene's data as JSON. The player adds the controls (play/pause, a crank-angle slider, a slider
 * per parameter, toggles for paths and vectors) and a readout, and moves the SVG's elements in place.
 * It computes nothing: every position and every number it shows is the package's, looked up by frame.
 * No network, no libraries.
 *
 * The crank angle and the family's members (the end of a parameter's range included):
 * - the crank-angle slider, the φ of the readout and the drawing always agree: the frame shown;
 * - a member that assembles over part of the turn is drawn only where it assembles: the crank angle the
 *   reader asked for (with the crank slider, or by playing) is shown if the member assembles there, the
 *   nearest frame where it does otherwise, and the slider moves there;
 * - a member that assembles at no frame draws nothing: the drawing is hidden, a message over the figure and
 *   the notes say why, the readout gives φ and "—" for every value, play is disabled; the crank slider
 *   still moves φ;
 * - the angle asked for is kept while the parameters move, so that passing through a member that assembles
 *   over less of the turn (or not at all) and coming back returns to it.
 *
 * For every reader (issue 32): every control is a native one, reached with Tab and worked by the keyboard
 * (arrow keys, Home and End on the sliders, Space on the play button or on a slider plays and pauses); each
 * slider is named with its unit and tells its value in that unit (aria-valuetext), not its position; the
 * values (with the explorer's parameters) are announced by a polite live region once the reader stops
 * changing them, or on pause, never
 * frame by frame while it plays; with the system's "reduced motion" the player does not animate (no play
 * button: the still and the sliders remain); the labels of the drawing are never smaller than 12 px on the
 * screen (on a phone they grow as the drawing shrinks).
 */
(function () {
  "use strict";

  function fmt(value, digits) {
    if (value === null || value === undefined) return "—";
    var text = value.toFixed(digits);
    if (/^-0(\.0*)?$/.test(text)) text = text.slice(1);       // no "−0.000"
    return text.replace("-", "\u2212");
  }

  function arrowPath(p, v, size) {
    var length = Math.hypot(v[0], v[1]);
    if (!(length > 0)) return "";
    var ux = v[0] / length, uy = v[1] / length;
    var tip = [p[0] + v[0], p[1] + v[1]];
    var head = Math.min(1.2 * size, 0.5 * length);
    var left = [tip[0] - head * ux - 0.5 * head * uy, tip[1] - head * uy + 0.5 * head * ux];
    var right = [tip[0] - head * ux + 0.5 * head * uy, tip[1] - head * uy - 0.5 * head * ux];
    return "M" + p[0] + "," + p[1] + " L" + tip[0] + "," + tip[1] + " M" + left[0] + "," + left[1] +
      " L" + tip[0] + "," + tip[1] + " L" + right[0] + "," + right[1];
  }

  function element(tag, attributes, text) {
    var node = document.createElement(tag);
    Object.keys(attributes || {}).forEach(function (key) { node.setAttribute(key, attributes[key]); });
    if (text !== undefined) node.textContent = text;
    return node;
  }

  function label(text) {              // a symbol as the book sets it: letters italic, "_t" a subscript t
    var span = element("span", { "class": "mech-symbol" }), parts = String(text).split(/_(.)/);
    parts.forEach(function (part, index) {
      var target = index % 2 ? span.appendChild(element("sub", {})) : span;
      part.split(/(\p{L}+)/u).forEach(function (piece, k) {
        if (piece) target.appendChild(k % 2 ? element("i", {}, piece) : document.createTextNode(piece));
      });
    });
    return span;
  }

  function rich(text) {               // a note: text, with symbols between dollars set as label() sets them
    var span = element("span", {});
    String(text).split(/\$([^$]*)\$/).forEach(function (part, index) {
      if (index % 2) span.appendChild(label(part));
      else if (part) span.appendChild(document.createTextNode(part));
    });
    return span;
  }

  function plain(text) { return String(text).replace(/_/g, ""); }     // "v_B" as a screen reader should say it

  var SETTLE = 400;                     // ms without a change before the values are announced
  var LEGIBLE = 12;                     // px: the smallest size of a label of the drawing on the screen
  var reducedMotion = window.matchMedia ? window.matchMedia("(prefers-reduced-motion: reduce)") : null;

  function Player(root) {
    var script = root.querySelector("script.mech-scene");
    this.root = root;
    this.svg = root.querySelector("svg.mech-still");
    this.data = JSON.parse(script.textContent);
    var still = (root.getAttribute("data-still") || "0,0").split(",");
    this.member = parseInt(still[0], 10);
    this.frame = parseInt(still[1], 10);
    this.wanted = this.frame;           // the frame the reader asked for (crank slider or play)
    this.empty = false;                 // the member shown assembles at no frame
    this.direction = 1;
    this.timer = null;
    this.announcing = null;
    this.reduced = Boolean(reducedMotion && reducedMotion.matches);
    this.build();
    this.setMember(this.member);
    root.classList.add("mech-ready");
  }

  // A point's stored positions, frame by frame (whole steps from the origin, null where it has none),
  // from the scene's form: two numbers for a point that does not move; otherwise the first position
  // the point has, then each next one as its difference from the one before (see scene.py).
  function decoded(xy, frames) {
    var out = [], x = 0, y = 0, k;
    for (k = 0; k < frames; k++) {
      var i = xy.length === 2 ? 0 : 2 * k;
      if (xy[i] === null) { out.push(null, null); continue; }
      if (xy.length === 2) { out.push(xy[0], xy[1]); continue; }
      x += xy[i]; y += xy[i + 1];
      out.push(x, y);
    }
    return out;
  }

  Player.prototype.at = function (name, frame) {
    var xy = this.positions[name], d = this.data;
    if (!xy || xy[2 * frame] === null) return null;
    return [d.origin[0] + d.step * xy[2 * frame], d.origin[1] + d.step * xy[2 * frame + 1]];
  };

  Player.prototype.build = function () {
    var d = this.data, self = this;
    var controls = element("div", { "class": "mech-controls" });
    this.play = element("button", { "type": "button", "class": "mech-play" });
    this.playIcon = this.play.appendChild(element("span", { "class": "mech-play-icon", "aria-hidden": "true" }, "\u25B6"));
    this.playText = this.play.appendChild(element("span", { "class": "mech-play-text" }, " play"));
    this.play.addEventListener("click", function () { self.toggle(); });
    controls.appendChild(this.play);
    var angle = element("label", { "class": "mech-slider" });
    angle.appendChild(element("span", { "class": "mech-slider-name" })).appendChild(label(d.angle));
    this.angle = element("input", { "type": "range", "class": "mech-angle", "min": "0",
      "max": String(d.phi.length - 1), "step": "1", "aria-label": "crank angle " + plain(d.angle) + ", in degrees" });
    this.angle.addEventListener("input", function () {
      self.stop(); self.turn(parseInt(self.angle.value, 10)); self.announceSoon();
    });
    this.angle.addEventListener("change", function () {     // a value set without an input event
      if (parseInt(self.angle.value, 10) !== self.frame) {
        self.stop(); self.turn(parseInt(self.angle.value, 10)); self.announceSoon();
      }
    });
    angle.appendChild(this.angle);
    controls.appendChild(angle);
    this.parameters = d.parameters.map(function (p, index) {
      var box = element("label", { "class": "mech-slider" });
      var name = element("span", { "class": "mech-slider-name" });
      name.appendChild(label(p.label));
      box.appendChild(name);
      var input = element("input", { "type": "range", "class": "mech-parameter", "min": "0",
        "max": String(p.values.length - 1), "step": "1", "data-name": p.name,
        "aria-label": plain(p.label) + (p.name && p.name !== p.label ? " (" + p.name + ")" : "") +
          (p.unit ? ", in " + p.unit : "") });
      var output = element("output", { "class": "mech-parameter-value", "data-name": p.name });
      var moved = function () {
        if (self.memberIndex() !== self.member) { self.setMember(self.memberIndex()); self.announceSoon(); }
      };
      input.addEventListener("input", moved);
      input.addEventListener("change", moved);
      box.appendChild(input);
      box.appendChild(output);
      controls.appendChild(box);
      return { input: input, output: output, spec: p, index: index };
    });
    // a toggle per kind of thing drawn: [its name, its text, whether an element of the drawing is of it]
    var toggles = [];
    if (d.paths.length) {
      toggles.push(["mech-path", "paths", function (e) { return e.classList.contains("mech-path"); }]);
    }
    var kinds = [];
    d.arrows.forEach(function (a) { if (kinds.indexOf(a.kind) < 0) kinds.push(a.kind); });
    kinds.forEach(function (kind) {      // any word, spaces included ("Frenet frame"): matched, not a class
      toggles.push(["kind-" + kind, kind, function (e) { return e.getAttribute("data-kind") === kind; }]);
    });
    toggles.forEach(function (pair) {
      var toggle = element("label", { "class": "mech-toggle" });
      var box = element("input", { "type": "checkbox", "checked": "checked", "data-toggle": pair[0] });
      box.addEventListener("change", function () {
        self.svg.querySelectorAll(".mech-path, [data-kind]").forEach(function (e) {
          if (pair[2](e)) e.classList.toggle("mech-off", !box.checked);
        });
      });
      toggle.appendChild(box);
      toggle.appendChild(document.createTextNode(" " + pair[1]));
      controls.appendChild(toggle);
    });
    // the figure and, over it, the message of a member that assembles at no frame
    var stage = element("div", { "class": "mech-stage" });
    this.svg.parentNode.insertBefore(stage, this.svg);
    stage.appendChild(this.svg);
    this.message = stage.appendChild(element("div", { "class": "mech-message", "role": "status" }));
    this.readout = element("div", { "class": "mech-readout", "aria-live": "off" });
    this.notes = element("div", { "class": "mech-notes" });
    // what a screen reader hears: the readout and the notes, once the reader has stopped changing them
    this.live = element("div", { "class": "mech-live", "role": "status", "aria-live": "polite", "aria-atomic": "true" });
    var caption = this.root.querySelector(".mech-caption");
    this.root.insertBefore(controls, caption);
    this.root.insertBefore(this.readout, caption);
    this.root.insertBefore(this.notes, caption);
    this.root.insertBefore(this.live, caption);
    // Space plays and pauses from a slider too (a slider does nothing with it); the button has it natively
    controls.addEventListener("keydown", function (event) {
      if ((event.key === " " || event.key === "Spacebar") && event.target.type === "range") {
        event.preventDefault();
        self.toggle();
      }
    });
    this.fitText();
    if (window.ResizeObserver) new window.ResizeObserver(function () { self.fitText(); }).observe(this.svg);
    else window.addEventListener("resize", function () { self.fitText(); });
    this.keys = d.keys;
    // the member shown first is the still's: set the parameter sliders to it
    var key = d.keys[this.member] || [];
    this.parameters.forEach(function (p) {
      p.input.value = String(p.spec.values.indexOf(key[p.index]));
    });
  };

  Player.prototype.memberIndex = function () {
    var index = 0;
    this.parameters.forEach(function (p) {
      index = index * p.spec.values.length + parseInt(p.input.value, 10);
    });
    return index;
  };

  Player.prototype.valid = function (frame) { return this.current.valid.charAt(frame) === "1"; };

  Player.prototype.nearestValid = function (frame) {
    var n = this.data.phi.length;
    for (var k = 0; k < n; k++) {
      var up = (frame + k) % n, down = ((frame - k) % n + n) % n;
      if (this.valid(up)) return up;
      if (this.valid(down)) return down;
    }
    return -1;
  };

  Player.prototype.setMember = function (index) {
    var d = this.data, self = this;
    this.member = index;
    this.current = d.members[index];
    this.positions = {};
    Object.keys(this.current.xy).forEach(function (name) {
      self.positions[name] = decoded(self.current.xy[name], d.phi.length);
    });
    this.parameters.forEach(function (p) {
      var value = p.spec.values[parseInt(p.input.value, 10)];
      p.output.textContent = " = " + fmt(value, p.spec.digits) + (p.spec.unit ? " " + p.spec.unit : "");
      p.input.setAttribute("aria-valuetext", fmt(value, p.spec.digits) + (p.spec.unit ? " " + p.spec.unit : ""));
    });
    this.svg.querySelectorAll(".mech-path").forEach(function (path) {
      path.setAttribute("d", self.pathData(path.getAttribute("data-point")));
    });
    this.svg.querySelectorAll(".mech-guide").forEach(function (g) {
      var guide = self.current.guides[parseInt(g.getAttribute("data-guide"), 10)];
      g.setAttribute("transform", "translate(" + guide[0] + " " + guide[1] + ") rotate(" +
        (guide[2] * 180 / Math.PI) + ")");
    });
    var full = this.current.valid.indexOf("0") < 0, none = this.current.valid.indexOf("1") < 0;
    var gaps = this.pointGaps();
    var notes = [];
    var arcs = [], points = [];              // an interval whose ends print alike is a single angle
    this.current.intervals.forEach(function (i) {
      var a = fmt(i[0], 1) + "°", b = fmt(i[1], 1) + "°";
      if (a === b) points.push(a); else arcs.push("[" + a + ", " + b + "]");
    });
    var range = (arcs.length ? "$" + d.angle + "$ in " + arcs.join(" and ") : "") +
      (points.length ? (arcs.length ? " and at " : "$" + d.angle + "$ = ") + points.join(" and ") : "");
    if (none && !this.current.intervals.length) {
      notes.push("does not assemble at any crank angle");
    } else if (none) {                        // a range narrower than a frame's step: between two frames
      notes.push("assembles only for " + range + ", between the frames of this figure");
    } else if (!full && gaps) {               // cut at points only (a change point): "[−180.0°, 180.0°]" misleads
      notes.push("assembles at every $" + d.angle + "$ but " + gaps.map(function (g) {
        return fmt(g, 1) + "°";
      }).join(" and "));
    } else if (!full) {
      notes.push("assembles only for " + range);
    }
    if (this.reduced) notes.push("not animated: the system asks for reduced motion; the sliders turn the crank");
    this.notes.textContent = "";
    this.notes.appendChild(rich(notes.concat(this.current.notes).join(" · ")));
    this.message.textContent = "";
    if (none) this.message.appendChild(rich(notes[0] + ": nothing to draw"));
    this.root.classList.toggle("mech-partial", !full);
    if (full) this.direction = 1;             // a full turn plays forwards, whatever a rocking member left
    this.show(this.wanted);
  };

  Player.prototype.pointGaps = function () {   // the angles (°) where the turn is cut, if every cut is < 0.05°
    var intervals = this.current.intervals.slice().sort(function (a, b) { return a[0] - b[0]; }), gaps = [];
    for (var k = 0; k < intervals.length; k++) {
      var end = intervals[k][1], next = k + 1 < intervals.length ? intervals[k + 1][0] : intervals[0][0] + 360;
      if (next - end >= 0.05) return null;
      var middle = (((end + next) / 2 + 180) % 360 + 360) % 360 - 180;     // in [−180°, 180°)
      gaps.push(middle === -180 ? 180 : middle);
    }
    return gaps.length ? gaps : null;
  };

  Player.prototype.turn = function (frame) {     // the reader (or play) turns the crank to a frame
    this.show(frame);
    this.wanted = this.frame;
  };

  Player.prototype.pathData = function (name) {
    var out = [], pen = false, n = this.data.phi.length;
    for (var k = 0; k < n; k++) {
      var p = this.at(name, k);
      if (p === null) { pen = false; continue; }
      out.push((pen ? "L" : "M") + p[0] + "," + p[1]);
      pen = true;
    }
    return out.join(" ") + (this.current.valid.indexOf("0") < 0 && out.length ? " Z" : "");
  };

  Player.prototype.show = function (frame) {   // the frame asked for, or the nearest where the member assembles
    var d = this.data, self = this;
    var found = this.nearestValid(frame);
    this.empty = found < 0;
    this.root.classList.toggle("mech-empty", this.empty);
    if (this.empty) this.stop();
    this.play.disabled = this.empty;
    this.play.hidden = this.reduced;         // reduced motion: no animation, the still and the sliders remain
    if (this.empty) this.play.title = "this member assembles at no crank angle of the figure";
    else this.play.removeAttribute("title");
    if (!this.empty) frame = found;          // nothing to draw: the angle asked for, read out alone
    this.frame = frame;
    this.angle.value = String(frame);
    var degrees = ((d.phi[frame] % 360) + 360) % 360;
    this.angle.setAttribute("aria-valuetext", fmt(degrees, Number.isInteger(degrees) ? 0 : 1) + " degrees");
    if (!this.empty) this.draw(frame);
    this.readout.textContent = "";
    var items = [[d.angle, d.phi[frame], 0, "°"]];
    d.readout.forEach(function (r, index) {
      items.push([r.label, self.empty ? null : self.current.values[index][frame], r.digits, r.unit]);
    });
    items.forEach(function (item, index) {
      var span = element("span", { "class": "mech-item" });
      span.appendChild(label(item[0]));
      span.appendChild(document.createTextNode(" = "));
      var value = index === 0 ? ((item[1] % 360) + 360) % 360 : item[1];
      span.appendChild(element("span", { "class": "mech-value", "data-label": item[0] },
        fmt(value, index === 0 ? (Number.isInteger(value) ? 0 : 1) : item[2])));
      if (item[3]) span.appendChild(document.createTextNode(item[3] === "°" ? "°" : " " + item[3]));
      self.readout.appendChild(span);
    });
  };

  Player.prototype.draw = function (frame) {    // the member's drawing at a frame where it assembles
    var d = this.data, self = this, size = d.size;
    var list = function (names) {
      return names.split(",").map(function (n) { return self.at(n, frame); })
        .filter(function (p) { return p !== null; })
        .map(function (p) { return p[0] + "," + p[1]; }).join(" ");
    };
    this.svg.querySelectorAll(".mech-bar, .mech-line").forEach(function (line) {
      line.setAttribute("points", list(line.getAttribute("data-points")));
    });
    this.svg.querySelectorAll(".mech-hinge, .mech-dot").forEach(function (c) {
      var p = self.at(c.getAttribute("data-joint"), frame);
      c.style.display = p ? "" : "none";
      if (p) { c.setAttribute("cx", p[0]); c.setAttribute("cy", p[1]); }
    });
    this.svg.querySelectorAll(".mech-ground").forEach(function (g) {
      var p = self.at(g.getAttribute("data-joint"), frame);
      g.style.display = p ? "" : "none";
      if (p) g.setAttribute("transform", "translate(" + p[0] + " " + p[1] + ")");
    });
    this.svg.querySelectorAll(".mech-block").forEach(function (g) {
      var p = self.at(g.getAttribute("data-joint"), frame);
      var a = g.getAttribute("data-angle"), angle = parseFloat(a);
      if (isNaN(angle)) {
        var values = self.current.angles[a] || [];
        angle = values[frame] === null || values[frame] === undefined ? 0 : values[frame];
      }
      g.style.display = p ? "" : "none";
      if (p) g.setAttribute("transform", "translate(" + p[0] + " " + p[1] + ") rotate(" + (angle * 180 / Math.PI) + ")");
    });
    this.svg.querySelectorAll(".mech-label").forEach(function (t) {
      var p = self.at(t.getAttribute("data-joint"), frame);
      t.style.display = p ? "" : "none";
      if (p) { t.setAttribute("x", p[0] + 0.6 * size); t.setAttribute("y", -p[1] - 0.6 * size); }
    });
    d.arrows.forEach(function (a, index) {
      var vector = self.current.vectors[index], p = self.at(a.at, frame);
      var path = self.svg.querySelector('.mech-arrow[data-arrow="' + index + '"]');
      var label = self.svg.querySelector('.mech-arrow-label[data-arrow="' + index + '"]');
      var shown = p !== null && vector[2 * frame] !== null;
      var v = shown ? [vector[2 * frame] * d.step, vector[2 * frame + 1] * d.step] : [0, 0];
      path.setAttribute("d", shown ? arrowPath(p, v, size) : "");
      label.style.display = shown ? "" : "none";
      if (shown) { label.setAttribute("x", p[0] + v[0] + 0.4 * size); label.setAttribute("y", -(p[1] + v[1]) - 0.4 * size); }
    });
  };

  Player.prototype.toggle = function () { if (this.timer) this.stop(); else this.start(); };

  Player.prototype.start = function () {
    var self = this;
    if (this.empty || this.timer || this.reduced) return;
    this.playIcon.textContent = "\u275A\u275A";
    this.playText.textContent = " pause";
    window.clearTimeout(this.announcing);    // nothing is announced while it plays
    this.timer = window.setInterval(function () { self.step(); }, 80);
  };

  Player.prototype.stop = function () {
    if (!this.timer) return;
    window.clearInterval(this.timer);
    this.timer = null;
    this.playIcon.textContent = "\u25B6";
    this.playText.textContent = " play";
    this.announceSoon();                      // paused: say where it stopped
  };

  Player.prototype.setReduced = function (reduced) {   // the system's "reduced motion" changed
    this.reduced = reduced;
    if (reduced) this.stop();
    this.setMember(this.member);
  };

  Player.prototype.announceSoon = function () {   // the values, once they have stopped changing for SETTLE ms
    var self = this;
    window.clearTimeout(this.announcing);
    this.announcing = window.setTimeout(function () {
      var items = [].map.call(self.readout.querySelectorAll(".mech-item"), function (item) {
        return item.textContent;
      });
      var settings = self.parameters.map(function (p) {   // the family member: each parameter's value
        return plain(p.spec.label) + p.output.textContent;
      });
      var notes = self.notes.textContent, message = self.empty ? self.message.textContent : "";
      self.live.textContent = [settings.join("; "), message || items.join("; "), notes].filter(Boolean).join(". ");
    }, SETTLE);
  };

  Player.prototype.fitText = function () {   // the drawing's labels at least LEGIBLE px high on the screen
    var box = this.svg.viewBox && this.svg.viewBox.baseVal, rect = this.svg.getBoundingClientRect();
    if (!box || !box.width || !box.height || !rect.width || !rect.height) return;
    var scale = Math.min(rect.width / box.width, rect.height / box.height);
    this.svg.querySelectorAll(".mech-text").forEach(function (group) {
      if (!group.hasAttribute("data-font-size")) group.setAttribute("data-font-size", group.getAttribute("font-size"));
      var base = parseFloat(group.getAttribute("data-font-size"));
      if (base > 0) group.setAttribute("font-size", String(Math.max(base, LEGIBLE / scale)));
    });
  };

  Player.prototype.step = function () {
    // a full turn plays round and round; a member that assembles over part of the turn rocks back
    // and forth inside the range where it assembles (as a crank driven back at each limit would)
    var n = this.data.phi.length, self = this;
    var after = function () { return ((self.frame + self.direction) % n + n) % n; };
    var next = after();
    if (!this.valid(next)) {                  // an arc may cross φ = 0: turn back only where it ends
      this.direction = -this.direction;
      next = after();
      if (!this.valid(next)) return;
    }
    this.turn(next);
  };

  function start() {
    if (reducedMotion && !start.listening) {
      start.listening = true;
      var changed = function () {
        document.querySelectorAll("div.mech-player").forEach(function (root) {
          if (root.mechPlayer) root.mechPlayer.setReduced(reducedMotion.matches);
        });
      };
      if (reducedMotion.addEventListener) reducedMotion.addEventListener("change", changed);
      else if (reducedMotion.addListener) reducedMotion.addListener(changed);
    }
    document.querySelectorAll("div.mech-player").forEach(function (root) {
      if (root.classList.contains("mech-ready")) return;
      try {
        root.mechPlayer = new Player(root);
      } catch (error) {
        root.classList.add("mech-failed");
        if (window.console) window.console.error("mechanisms player:", error);
      }
    });
  }

  if (document.readyState === "loading") document.addEventListener("DOMContentLoaded", start);
  else start();
})();
