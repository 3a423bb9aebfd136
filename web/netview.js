// Moving about the network and moving its nodes, as in Houdini's network editor: drag on
// the background pans, the wheel zooms about the pointer (10% a notch, 0.2x to 3x), Fit
// shows every node; dragging a node moves it, and the drop is one undoable edit of the
// node's `position` in the graph, so Save writes only that line. The view itself (pan and
// zoom) is the page's, not the graph's: it is never saved.
"use strict";

const NET_ZOOM = { step: 1.1, min: 0.2, max: 3, dragThreshold: 3 };
const netView = { x: 0, y: 0, scale: 1, dragged: false };
const network = { boxes: {}, redrawWires: () => {} };  // set by drawNetwork

function showView(svg) {
  svg.querySelector("g.world")?.setAttribute(
    "transform", `translate(${netView.x},${netView.y}) scale(${netView.scale})`);
}

// The network's coordinates of a pointer event.
function toWorld(svg, e) {
  const r = svg.getBoundingClientRect();
  return { x: (e.clientX - r.left - netView.x) / netView.scale,
           y: (e.clientY - r.top - netView.y) / netView.scale };
}

// Zooms by `factor` keeping the network's point under (px, py), pane pixels, in place.
function zoomAbout(svg, px, py, factor) {
  const scale = Math.min(Math.max(netView.scale * factor, NET_ZOOM.min), NET_ZOOM.max);
  netView.x = px - ((px - netView.x) * scale) / netView.scale;
  netView.y = py - ((py - netView.y) * scale) / netView.scale;
  netView.scale = scale;
  showView(svg);
}

// Every node in view, at most at full size, below the Fit button.
function fitView(svg) {
  const boxes = Object.values(network.boxes);
  if (!boxes.length) return;
  const x0 = Math.min(...boxes.map((b) => b.x)), y0 = Math.min(...boxes.map((b) => b.y));
  const x1 = Math.max(...boxes.map((b) => b.x + NODE_WIDTH));
  const y1 = Math.max(...boxes.map((b) => b.y + b.height));
  const r = svg.getBoundingClientRect();
  const scale = Math.min(1, (r.width - 24) / (x1 - x0), (r.height - 48) / (y1 - y0));
  netView.scale = Math.max(scale, NET_ZOOM.min);
  netView.x = 12 - x0 * netView.scale;
  netView.y = 36 - y0 * netView.scale;
  showView(svg);
}

// A drag of the background (pan) or of a node (move); ports belong to the wiring.
function startNetDrag(svg, e) {
  if (e.button !== 0 || e.target.closest?.("circle.port")) return null;
  const g = e.target.closest?.("g.node");
  const start = { x: e.clientX, y: e.clientY };
  if (!g) return { kind: "pan", start, from: { x: netView.x, y: netView.y } };
  const id = g.dataset.node;
  const box = network.boxes[id];
  return { kind: "node", start, id, g, box, from: { x: box.x, y: box.y } };
}

function moveNetDrag(svg, drag, e) {
  const dx = e.clientX - drag.start.x, dy = e.clientY - drag.start.y;
  if (Math.hypot(dx, dy) >= NET_ZOOM.dragThreshold) drag.moved = true;
  if (!drag.moved) return;
  if (drag.kind === "pan") {
    netView.x = drag.from.x + dx;
    netView.y = drag.from.y + dy;
    showView(svg);
    return;
  }
  drag.box.x = Math.round(drag.from.x + dx / netView.scale);
  drag.box.y = Math.round(drag.from.y + dy / netView.scale);
  drag.g.setAttribute("transform", `translate(${drag.box.x},${drag.box.y})`);
  network.redrawWires();
}

// onMove(id, [x, y]) when a node was dropped somewhere else.
function enableNetView(svg, onMove) {
  let drag = null;
  svg.addEventListener("pointerdown", (e) => {
    drag = startNetDrag(svg, e);
    if (!drag) return;
    try { svg.setPointerCapture(e.pointerId); } catch (err) { /* a synthetic pointer */ }
  });
  svg.addEventListener("pointermove", (e) => { if (drag) moveNetDrag(svg, drag, e); });
  const end = () => {
    if (!drag) return;
    const done = drag;
    drag = null;
    netView.dragged = Boolean(done.moved);  // the click that follows a drag selects nothing
    setTimeout(() => { netView.dragged = false; }, 0);
    if (done.kind === "node" && done.moved) onMove(done.id, [done.box.x, done.box.y]);
  };
  svg.addEventListener("pointerup", end);
  window.addEventListener("pointerup", end);
  svg.addEventListener("wheel", (e) => {
    e.preventDefault();
    const r = svg.getBoundingClientRect();
    zoomAbout(svg, e.clientX - r.left, e.clientY - r.top,
              e.deltaY < 0 ? NET_ZOOM.step : 1 / NET_ZOOM.step);
  }, { passive: false });
  $("fit").addEventListener("click", () => fitView(svg));
}
