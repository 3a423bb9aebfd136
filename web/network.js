// The node network as SVG, flowing down as Houdini's does: each node a box with its typed
// ports (inputs on the left edge, outputs on the right), at the graph file's `position` of
// the node or, without one, in rows by depth (a node one row below its deepest input),
// wires as curves from output to input. Everything is drawn in one group, `g.world`, that
// netview.js pans and zooms.
"use strict";

const NODE_WIDTH = 200, PORT_ROW = 15, HEADER = 32, COLUMN_GAP = 36, ROW_GAP = 34;
const GROUP_COLOURS = {
  atmosphere: "#d8ecf7", fluid: "#dbeedd", mapping: "#f4e6c8", volume: "#e8dcf2",
  render: "#f7d9d4", io: "#e4e4e4", util: "#eeeeee",
};

function svgElement(tag, attrs, parent) {
  const el = document.createElementNS("http://www.w3.org/2000/svg", tag);
  for (const [k, v] of Object.entries(attrs)) el.setAttribute(k, v);
  if (parent) parent.appendChild(el);
  return el;
}

// { id: {x, y, height, outputRow} } for graph.nodes, given the declarations of their types:
// a node's own position where the file gives one, else its place in the rows by depth.
function layoutNetwork(nodes, types) {
  const depth = {};
  const depthOf = (id, seen = new Set()) => {
    if (id in depth) return depth[id];
    if (seen.has(id)) return 0;
    seen.add(id);
    let d = 0;
    for (const source of Object.values(nodes[id].inputs || {})) {
      const upstream = source.split(".")[0];
      if (upstream in nodes) d = Math.max(d, depthOf(upstream, seen) + 1);
    }
    return (depth[id] = d);
  };
  const levels = [];
  for (const id of Object.keys(nodes).sort()) (levels[depthOf(id)] ||= []).push(id);
  const boxes = {};
  let y = 12;
  for (const ids of levels) {
    if (!ids) continue;
    let tallest = 0;
    ids.forEach((id, i) => {
      const decl = types[nodes[id].type];
      const height = HEADER + (decl.inputs.length + decl.outputs.length) * PORT_ROW + 4;
      boxes[id] = { x: 60 + i * (NODE_WIDTH + COLUMN_GAP), y, height,
                    outputRow: decl.inputs.length };
      tallest = Math.max(tallest, height);
    });
    y += tallest + ROW_GAP;
  }
  for (const [id, node] of Object.entries(nodes))
    if (node.position) [boxes[id].x, boxes[id].y] = node.position;
  return boxes;
}

// Wiring by dragging, as in Houdini: from an output port to an input port of its type
// connects them (replacing that input's wire); from a connected input port, the wire is
// picked up and dropped on another input of its type, or anywhere else to disconnect.
// onWire(changes): one edit, a list of {node, input, source} (source "node.port", or null to
// disconnect). nodesNow() gives the graph's nodes as the page has them now.
function enableWiring(svg, nodesNow, onWire) {
  let drag = null;  // { source, type, from: {x, y}, line, detach: {node, input} | null }
  const end = (target) => {
    if (!drag) return;
    const { source, type, detach, line } = drag;
    drag = null;
    line.remove();
    for (const c of svg.querySelectorAll(".port.can-drop")) c.classList.remove("can-drop");
    const into = target?.closest?.("circle.port[data-input]");
    const changes = [];
    if (into && into.dataset.type === type && into.dataset.node !== source.split(".")[0]) {
      if (detach) changes.push({ ...detach, source: null });
      changes.push({ node: into.dataset.node, input: into.dataset.input, source });
    } else if (detach && !into) {
      changes.push({ ...detach, source: null });
    }
    if (changes.length) onWire(changes);
  };
  svg.addEventListener("pointerdown", (e) => {
    const port = e.target.closest?.("circle.port");
    if (!port) return;
    e.preventDefault();
    e.stopPropagation();
    let source = null, detach = null;
    if (port.dataset.output) {
      source = `${port.dataset.node}.${port.dataset.output}`;
    } else {
      source = (nodesNow()[port.dataset.node].inputs || {})[port.dataset.input];
      if (!source) return;
      detach = { node: port.dataset.node, input: port.dataset.input };
    }
    const start = svg.querySelector(`circle.port[data-node="${source.split(".")[0]}"]` +
                                    `[data-output="${source.split(".")[1]}"]`);
    if (!start) return;
    const box = network.boxes[source.split(".")[0]];  // ports are drawn in their node's group
    const from = { x: box.x + Number(start.getAttribute("cx")),
                   y: box.y + Number(start.getAttribute("cy")) };
    const line = svgElement("line", { class: "wire dragging", x1: from.x, y1: from.y,
                                      x2: from.x, y2: from.y }, svg.querySelector("g.world"));
    drag = { source, type: start.dataset.type, from, line, detach };
    for (const c of svg.querySelectorAll(`circle.port[data-input][data-type="${drag.type}"]`))
      c.classList.add("can-drop");
  });
  svg.addEventListener("pointermove", (e) => {
    if (!drag) return;
    const p = toWorld(svg, e);
    drag.line.setAttribute("x2", p.x);
    drag.line.setAttribute("y2", p.y);
  });
  svg.addEventListener("pointerup", (e) => end(e.target));
  window.addEventListener("pointerup", (e) => { if (drag && !svg.contains(e.target)) end(null); });
}

const portY = (box, row) => box.y + HEADER + row * PORT_ROW + PORT_ROW / 2 - 2;

// The wires between `boxes`, replacing those drawn before (a dragged node's move redraws them).
function drawWires(world, nodes, types, boxes) {
  for (const old of world.querySelectorAll("path.wire")) old.remove();
  for (const [id, node] of Object.entries(nodes)) {
    const decl = types[node.type];
    for (const [input, source] of Object.entries(node.inputs || {})) {
      const [from, port] = source.split(".");
      if (!(from in boxes)) continue;
      const out = types[nodes[from].type].outputs.findIndex((p) => p.name === port);
      const into = decl.inputs.findIndex((p) => p.name === input);
      const x1 = boxes[from].x + NODE_WIDTH, y1 = portY(boxes[from], boxes[from].outputRow + out);
      const x2 = boxes[id].x, y2 = portY(boxes[id], into);
      const bend = Math.min(50, Math.max(30, Math.abs(x2 - x1) / 2));
      const d = `M${x1},${y1} C${x1 + bend},${y1} ${x2 - bend},${y2} ${x2},${y2}`;
      // First in the group, so that wires pass under the nodes.
      const wire = svgElement("path", { class: "wire", d });
      wire.dataset.wire = `${source}->${id}.${input}`;
      world.insertBefore(wire, world.firstChild);
    }
  }
}

// One node's box, title, stats and ports, drawn at the origin and moved to its place by the
// group's transform (so that a drag moves the group alone).
function drawNode(world, id, node, decl, box) {
  const g = svgElement("g", { class: "node", "data-node": id,
                              transform: `translate(${box.x},${box.y})` }, world);
  const at = { ...box, x: 0, y: 0 };
  svgElement("rect", { class: "body", x: 0, y: 0, width: NODE_WIDTH, height: box.height,
                       fill: GROUP_COLOURS[decl.category] || "#eee" }, g);
  const title = svgElement("text", { x: 6, y: 14, "font-weight": "bold" }, g);
  title.textContent = id;
  const type = svgElement("text", { x: 6, y: 27, fill: "#555" }, g);
  type.textContent = node.type;
  type.classList.add("type");
  const stats = svgElement("text", { x: NODE_WIDTH - 6, y: 14, "text-anchor": "end",
                                     fill: "#d9480f" }, g);
  stats.classList.add("stats");
  decl.inputs.forEach((p, i) => {
    svgElement("circle", { class: "port", cx: 0, cy: portY(at, i), r: 5,
                           "data-node": id, "data-input": p.name, "data-type": p.type }, g);
    const t = svgElement("text", { x: 8, y: portY(at, i) + 4 }, g);
    t.textContent = `${p.name}: ${p.type}`;
  });
  decl.outputs.forEach((p, i) => {
    const row = box.outputRow + i;
    svgElement("circle", { class: "port", cx: NODE_WIDTH, cy: portY(at, row), r: 5,
                           "data-node": id, "data-output": p.name, "data-type": p.type }, g);
    const t = svgElement("text", { x: NODE_WIDTH - 8, y: portY(at, row) + 4,
                                   "text-anchor": "end" }, g);
    t.textContent = `${p.name}: ${p.type}`;
  });
  return g;
}

// Draws the network into `svg`; onSelect(id) when a node is clicked. Returns the node
// groups by id, so that the page can mark what cooked.
function drawNetwork(svg, nodes, types, onSelect) {
  svg.replaceChildren();
  const world = svgElement("g", { class: "world" }, svg);
  const boxes = layoutNetwork(nodes, types);
  const groups = {};
  for (const [id, box] of Object.entries(boxes)) {
    groups[id] = drawNode(world, id, nodes[id], types[nodes[id].type], box);
    groups[id].addEventListener("click", () => { if (!netView.dragged) onSelect(id); });
  }
  drawWires(world, nodes, types, boxes);
  network.boxes = boxes;
  network.redrawWires = () => drawWires(world, nodes, types, boxes);
  showView(svg);
  return groups;
}
