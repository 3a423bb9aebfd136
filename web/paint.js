// Painting a map on its preview: with Paint ticked, a map's preview (one pixel a cell, north
// up, black 0 to white 1) becomes a canvas to paint grey values on with a round brush (full
// strength inside 70% of its radius, fading to nothing at its edge). "Use painting" sends the
// canvas to the server, which writes it as a new PNG under --out/paintings (never over a
// file), and makes it the graph's: a painted ReadMap reads the new file (one undoable edit
// of its `file`); any other map gets a new ReadMap beside it, with the painted node's cell
// size, to wire where the painting should go (one undoable edit of the graph).
"use strict";

const BRUSH_CORE = 0.7;  // the share of the radius painted at full strength
const paint = { stroke: null, node: null };

function paintCanvas() {
  return $("paint-canvas");
}

// The preview's choice when it shows a map: {id, port}, else null.
function paintedMap() {
  const choice = $("preview-node").value;
  const found = previewOutputs().find((o) => `${o.id}.${o.port}` === choice);
  return found?.type === "Map2D" ? found : null;
}

// The Paint controls show for a map's preview only; leaving a map ends painting.
function showPaintControls() {
  const map = paintedMap();
  $("paint-row").hidden = !map;
  if (!map || (paint.node && paint.node !== map.id)) stopPainting();
}

function startPainting() {
  const img = $("preview"), canvas = paintCanvas();
  if (!img.naturalWidth) {
    $("paint").checked = false;
    setStatus("nothing to paint on yet: cook the map first", true);
    return;
  }
  canvas.width = img.naturalWidth;
  canvas.height = img.naturalHeight;
  canvas.getContext("2d", { willReadFrequently: true }).drawImage(img, 0, 0);
  paint.node = paintedMap().id;
  img.hidden = true;
  canvas.hidden = false;
  $("paint-apply").disabled = false;
}

function stopPainting() {
  paint.node = null;
  paint.stroke = null;
  $("paint").checked = false;
  $("paint-apply").disabled = true;
  paintCanvas().hidden = true;
  $("preview").hidden = false;
}

// One dab of the brush at canvas pixel (x, y).
function dab(pixels, x, y, radius, grey) {
  const { width, height, data } = pixels;
  for (let py = Math.max(0, Math.floor(y - radius)); py <= Math.min(height - 1, y + radius); ++py)
    for (let px = Math.max(0, Math.floor(x - radius)); px <= Math.min(width - 1, x + radius); ++px) {
      const d = Math.hypot(px + 0.5 - x, py + 0.5 - y) / radius;
      if (d >= 1) continue;
      const weight = d <= BRUSH_CORE ? 1 : (1 - d) / (1 - BRUSH_CORE);
      const at = 4 * (py * width + px);
      const v = Math.round(data[at] + (grey - data[at]) * weight);
      data[at] = data[at + 1] = data[at + 2] = v;
    }
}

// Dabs from the stroke's last point to the pointer, a third of the radius apart.
function paintTo(e) {
  const canvas = paintCanvas(), r = canvas.getBoundingClientRect();
  const x = ((e.clientX - r.left) * canvas.width) / r.width;
  const y = ((e.clientY - r.top) * canvas.height) / r.height;
  const radius = Math.max(0.5, Number($("brush-radius").value) || 1);
  const grey = Math.round(255 * Math.min(Math.max(Number($("brush-value").value), 0), 1));
  const ctx = canvas.getContext("2d", { willReadFrequently: true });
  const pixels = ctx.getImageData(0, 0, canvas.width, canvas.height);
  const from = paint.stroke.last || { x, y };
  const steps = Math.max(1, Math.ceil(Math.hypot(x - from.x, y - from.y) / (radius / 3)));
  for (let i = 1; i <= steps; ++i)
    dab(pixels, from.x + ((x - from.x) * i) / steps, from.y + ((y - from.y) * i) / steps, radius, grey);
  ctx.putImageData(pixels, 0, 0);
  paint.stroke.last = { x, y };
}

// The canvas's grey as the server takes it: two hex digits a pixel, top row first.
function canvasHex(canvas) {
  const { data } = canvas.getContext("2d").getImageData(0, 0, canvas.width, canvas.height);
  let hex = "";
  for (let i = 0; i < data.length; i += 4) hex += data[i].toString(16).padStart(2, "0");
  return hex;
}

// A new ReadMap of `file` to the right of `id`, with id's cell size when it has one.
function addReadMap(id, file) {
  let n = 1;
  while (`paint${n}` in state.graph.nodes) ++n;
  const name = `paint${n}`;
  const source = state.graph.nodes[id];
  const cell = state.types[source.type].params.find((p) => p.name === "cellSize");
  const params = { file };
  if (cell) params.cellSize = paramValue(id, cell);
  const box = network.boxes[id];
  const position = [Math.round(box.x + NODE_WIDTH + 40), Math.round(box.y)];
  return editGraph((g) => { g.nodes[name] = { type: "ReadMap", params, position }; })
    .then(() => name);
}

async function usePainting() {
  const id = paint.node, canvas = paintCanvas();
  if (!id) return;
  let reply;
  try {
    reply = await api("/api/paint", { node: id, width: canvas.width, height: canvas.height,
                                      grey: canvasHex(canvas) });
  } catch (e) {
    setStatus(e.message, true);
    return;
  }
  stopPainting();
  if (state.graph.nodes[id].type === "ReadMap") {
    const decl = state.types.ReadMap.params.find((p) => p.name === "file");
    const before = paramValue(id, decl);
    if (!(await sendParam(id, "file", reply.file))) return;
    recordEdit({ kind: "param", node: id, param: "file", before, after: reply.file });
    if (state.selected === id) showParams(id);
    cook();
    return;
  }
  const name = await addReadMap(id, reply.file);
  if (name in state.graph.nodes) {
    $("preview-node").value = `${name}.map`;
    showPaintControls();
    setStatus(`painted ${reply.file}: wire ${name}.map where the painting should go`);
    cook();
  }
}

$("paint").addEventListener("change", () => ($("paint").checked ? startPainting() : stopPainting()));
$("paint-apply").addEventListener("click", () => usePainting());
$("preview-node").addEventListener("change", showPaintControls);
paintCanvas().addEventListener("pointerdown", (e) => {
  if (e.button !== 0) return;
  e.preventDefault();
  try { paintCanvas().setPointerCapture(e.pointerId); } catch (err) { /* a synthetic pointer */ }
  paint.stroke = { last: null };
  paintTo(e);
});
paintCanvas().addEventListener("pointermove", (e) => { if (paint.stroke) paintTo(e); });
window.addEventListener("pointerup", () => { paint.stroke = null; });
