// The page of `cloudgraph serve`: the network, the selected node's parameters (widgets made
// from the node declarations, every edit checked by the server as the CLI checks it), the
// preview of a renderer at the current frame, recooked after each edit, and the cook report.
// api.js holds the status line and the API, save.js Save and the file's changes on disk.
"use strict";

const state = {
  graph: null,        // the graph's JSON, as the server has it
  types: {},          // declarations of the node types in the graph
  groups: {},         // the network's SVG group of each node
  selected: null,     // the node whose parameters are shown
  cooking: false,
  watching: false,    // the progress bar polls while this is set
  wiring: false,      // the network's drag wiring is set up
  editing: 0,         // this page's edits under way (their new version is not read yet)
  again: false,       // an edit came during a cook: cook once more when it ends
  playing: false,
  version: 0,         // of the server's graph when this page last read it
  registry: [],       // every node type, for "Add"
};
// The outputs the preview can draw: images, density maps and particles (as points).
const PREVIEW_TYPES = ["Image", "Map2D", "VapourParticles", "Condensation", "CloudParticles"];

function previewOutputs() {
  const found = [];
  for (const [id, node] of Object.entries(state.graph.nodes))
    for (const port of state.types[node.type].outputs)
      if (PREVIEW_TYPES.includes(port.type)) found.push({ id, port: port.name, type: port.type });
  // Renderers first: what the preview is mostly for.
  return found.sort((a, b) => (a.type !== "Image") - (b.type !== "Image"));
}

function paramValue(id, decl) {
  const params = state.graph.nodes[id].params || {};
  return decl.name in params ? params[decl.name] : decl.default;
}

// One widget per declared parameter; a change is sent at once.
function showParams(id) {
  state.selected = id;
  for (const [other, g] of Object.entries(state.groups)) g.classList.toggle("selected", other === id);
  const decl = state.types[state.graph.nodes[id].type];
  $("params-title").textContent = `${id} (${decl.type})`;
  $("params-doc").textContent = decl.doc;
  const form = $("params");
  form.replaceChildren();
  for (const p of decl.params) {
    const label = document.createElement("label");
    label.title = p.doc;
    const name = document.createElement("span");
    name.textContent = p.units ? `${p.name} (${p.units})` : p.name;
    label.appendChild(name);
    const editor = document.createElement("span");
    const value = paramValue(id, p);
    const inputs = [];
    const numberInput = (v, integer) => {
      const input = document.createElement("input");
      input.type = "number";
      input.step = integer ? "1" : "any";
      if (p.min !== null && isFinite(p.min)) input.min = p.min;
      if (p.max !== null && isFinite(p.max)) input.max = p.max;
      input.value = v;
      return input;
    };
    let read;
    if (p.type === "bool") {
      const input = document.createElement("input");
      input.type = "checkbox";
      input.checked = value;
      inputs.push(input);
      read = () => input.checked;
    } else if (p.choices && p.choices.length) {
      const select = document.createElement("select");
      for (const c of p.choices) select.add(new Option(c, c, false, c === value));
      inputs.push(select);
      read = () => select.value;
    } else if (p.type === "float" || p.type === "int") {
      const input = numberInput(value, p.type === "int");
      if (wantsSlider(p)) inputs.push(sliderFor(p, input));  // first: what the eye finds
      inputs.push(input);
      read = () => Number(input.value);
    } else if (p.type === "vec3") {
      for (const v of value) inputs.push(numberInput(v, false));
      read = () => inputs.map((i) => Number(i.value));
    } else if (p.type === "string") {
      const input = document.createElement("input");
      input.value = value;
      if (p.role === "input_file") {  // suggestions: the files beside the graph
        input.setAttribute("list", "graph-files");
        input.placeholder = "a file, relative to the graph";
      } else if (p.role === "output_path") {
        input.placeholder = "a file under --out (#### = frame)";
      }
      inputs.push(input);
      read = () => input.value;
    } else {  // lists: edited as JSON
      const input = document.createElement("input");
      input.value = JSON.stringify(value);
      inputs.push(input);
      read = () => JSON.parse(input.value);
    }
    const message = document.createElement("span");
    message.className = "error";
    for (const input of inputs) {
      input.dataset.param = p.name;
      editor.appendChild(input);
      input.addEventListener("change", () => editParam(id, p.name, read, message));
    }
    if (isColour(p))
      editor.appendChild(colourPickerFor(inputs, () => editParam(id, p.name, read, message)));
    label.appendChild(editor);
    form.appendChild(label);
    form.appendChild(message);
  }
  showInputs(id);
}

// Each input port as a menu of the outputs of its type, "(none)" to disconnect.
function showInputs(id) {
  const node = state.graph.nodes[id];
  const decl = state.types[node.type];
  const box = $("inputs");
  box.replaceChildren();
  for (const port of decl.inputs) {
    const label = document.createElement("label");
    const name = document.createElement("span");
    name.textContent = `${port.name}: ${port.type}`;
    label.appendChild(name);
    const select = document.createElement("select");
    select.dataset.input = port.name;
    select.add(new Option("(none)", ""));
    for (const [other, n] of Object.entries(state.graph.nodes)) {
      if (other === id) continue;
      for (const out of state.types[n.type]?.outputs || [])
        if (out.type === port.type) select.add(new Option(`${other}.${out.name}`, `${other}.${out.name}`));
    }
    select.value = (node.inputs || {})[port.name] || "";
    select.addEventListener("change",
                            () => rewire([{ node: id, input: port.name, source: select.value || null }]));
    label.appendChild(select);
    box.appendChild(label);
  }
}

// A wiring edit: the edited graph goes to the server, which loads it with the same type
// checks as a file; on success the page redraws from the server's graph.
async function editGraph(edit) {
  const before = JSON.parse(JSON.stringify(state.graph));
  const graph = JSON.parse(JSON.stringify(state.graph));
  edit(graph);
  if (!(await sendGraph(graph))) {
    showParams(state.selected);  // back to the graph as it is
    return;
  }
  recordEdit({ kind: "graph", before, after: graph });
  cook();
}

// Sends a whole graph; true when the server took it (the page then shows the server's).
async function sendGraph(graph) {
  state.editing++;
  try {
    await api("/api/graph", { graph });
    markEdited();
    await reload();
    return true;
  } catch (e) {
    setStatus(e.message, true);
    return false;
  } finally {
    state.editing--;
  }
}

// Connects or disconnects inputs in one wiring edit: changes [{node, input, source}], source
// "node.port" or null.
function rewire(changes) {
  return editGraph((g) => {
    for (const { node, input, source } of changes) {
      const inputs = (g.nodes[node].inputs ||= {});
      if (source) inputs[input] = source; else delete inputs[input];
    }
  });
}

// A node dropped at `position` in the network: one edit of its "position".
function moveNode(id, position) {
  return editGraph((g) => { g.nodes[id].position = position; });
}

async function editParam(id, name, read, message) {
  message.textContent = "";
  let value;
  try {
    value = read();
  } catch (e) {
    message.textContent = `not JSON: ${e.message}`;
    return;
  }
  const decl = state.types[state.graph.nodes[id].type].params.find((p) => p.name === name);
  const before = paramValue(id, decl);
  if (!(await sendParam(id, name, value, message))) return;
  recordEdit({ kind: "param", node: id, param: name, before, after: value });
  cook();
}

// Sets one parameter; true when the server took it. A refusal is the CLI's own message,
// naming node and parameter, in the status line and `message` when given.
async function sendParam(id, name, value, message) {
  state.editing++;
  try {
    const reply = await api("/api/param", { node: id, param: name, value });
    (state.graph.nodes[id].params ||= {})[name] = value;
    state.version = reply.version;
    markEdited();
  } catch (e) {
    if (message) message.textContent = e.message;
    setStatus(e.message, true);
    return false;
  } finally {
    state.editing--;
  }
  setStatus(`${id}.${name} = ${JSON.stringify(value)}`);
  return true;
}

function showReport(report, seconds) {
  const body = $("report").tBodies[0];
  body.replaceChildren();
  for (const g of Object.values(state.groups)) {
    g.classList.remove("cooked", "cooking");
    g.querySelector(".stats").textContent = "";
  }
  for (const r of report.records || []) {
    const row = body.insertRow();
    row.dataset.node = r.node;
    row.dataset.status = r.status;
    for (const text of [r.node, r.status, r.reason || "", (r.seconds || 0).toFixed(3)])
      row.insertCell().textContent = text;
    const g = state.groups[r.node];
    if (!g) continue;
    if (r.status === "cooked") g.classList.add("cooked");
    g.querySelector(".stats").textContent =
      r.status === "cooked" ? `${(r.seconds || 0).toFixed(2)} s` : r.status;
  }
  setStatus(`cooked frame ${$("frame").value} in ${seconds.toFixed(2)} s`);
}

// The nodes `node` needs, itself included (the ones a cook of it may visit).
function upstreamOf(node) {
  const seen = new Set();
  const visit = (id) => {
    if (seen.has(id) || !state.graph.nodes[id]) return;
    seen.add(id);
    for (const source of Object.values(state.graph.nodes[id].inputs || {}))
      visit(source.split(".")[0]);
  };
  visit(node);
  return seen;
}

// While a cook runs: the server's count of node-frames done, the time so far, the finished
// nodes outlined green and those now cooking (needed, their inputs done) dashed blue.
function showProgress(target, p) {
  $("progress-row").hidden = false;
  $("progress").max = Math.max(p.total, 1);
  $("progress").value = p.done;
  $("progress-text").textContent = `${p.done} / ${p.total} · ${p.seconds.toFixed(1)} s`;
  const finished = new Set(p.finished);
  for (const id of upstreamOf(target)) {
    const g = state.groups[id];
    if (!g) continue;
    const inputs = Object.values(state.graph.nodes[id].inputs || {}).map((s) => s.split(".")[0]);
    g.classList.toggle("done", finished.has(id));
    g.classList.toggle("cooking", !finished.has(id) && inputs.every((i) => finished.has(i)));
  }
}

async function watchProgress(target) {
  state.watching = true;
  while (state.watching) {
    await new Promise((resolve) => setTimeout(resolve, 250));
    if (!state.watching) break;
    try {
      const p = await api("/api/progress");
      if (p.cooking && state.watching) showProgress(target, p);
    } catch (e) { /* the cook's own reply says what went wrong */ }
  }
  $("progress-row").hidden = true;
  for (const g of Object.values(state.groups)) g.classList.remove("done", "cooking");
}

// Cooks the chosen renderer at the current frame; an edit during a cook cancels it and
// cooks again when it has stopped.
async function cook() {
  const choice = $("preview-node").value;
  if (!choice) return;
  if (state.cooking) {
    state.again = true;
    api("/api/cancel", {}).catch(() => {});
    return;
  }
  state.cooking = true;
  document.body.dataset.cooking = "yes";  // for tests
  $("cancel").disabled = false;
  const [node, port] = choice.split(".");
  state.groups[node]?.classList.add("cooking");
  const frame = Number($("frame").value);
  setStatus(`cooking ${node} at frame ${frame}…`);
  const watching = watchProgress(node);
  try {
    const reply = await api("/api/cook", { node, port, frame, write: $("write").checked });
    showReport(reply.report, reply.seconds);
    if (reply.preview) $("preview").src = await keepPreview(frame, reply.preview);
    const type = previewOutputs().find((o) => `${o.id}.${o.port}` === choice)?.type;
    $("preview").classList.toggle("cells", type === "Map2D");  // a map's cells stay square
  } catch (e) {
    setStatus(e.message, true);
  } finally {
    state.watching = false;
    await watching;
    state.cooking = false;
    delete document.body.dataset.cooking;
    document.body.dataset.cooks = Number(document.body.dataset.cooks || 0) + 1;  // for tests
    $("cancel").disabled = true;
  }
  if (state.again) {
    state.again = false;
    cook();
  } else if (state.playing) {
    playStep();
  }
}

// Reads the server's graph and redraws, keeping the frame, the preview choice and the
// selected node where they still exist.
async function reload() {
  const reply = await api("/api/graph");
  const files = (await api("/api/files")).files;
  $("graph-files").replaceChildren(...files.map((f) => new Option(f, f)));
  state.graph = reply.graph;
  state.types = reply.types;
  state.registry = reply.registry;
  state.version = reply.version;
  $("file").textContent = reply.file;
  if (reply.fileError) setStatus(`the file on disk does not load: ${reply.fileError}`, true);
  const frames = state.graph.frames;
  const slider = $("frame");
  const frame = Math.min(Math.max(Number(slider.value), frames.start), frames.end);
  slider.min = frames.start;
  slider.max = frames.end;
  slider.value = frame;
  $("frame-value").textContent = slider.value;
  state.groups = drawNetwork($("network"), state.graph.nodes, state.types, showParams);
  if (!state.wiring) {  // once: the svg element stays, its contents are redrawn
    state.wiring = true;
    enableWiring($("network"), () => state.graph.nodes, rewire);
    enableNetView($("network"), moveNode);
    fitView($("network"));
  }
  const select = $("preview-node");
  const chosen = select.value;
  select.replaceChildren();
  for (const { id, port, type } of previewOutputs())
    select.add(new Option(type === "Image" ? id : `${id}.${port} (${type})`, `${id}.${port}`));
  if ([...select.options].some((o) => o.value === chosen)) select.value = chosen;
  showPaintControls();
  const types = $("add-type");
  if (!types.options.length) for (const t of state.registry) types.add(new Option(t, t));
  const ids = Object.keys(state.graph.nodes).sort();
  const keep = ids.includes(state.selected) ? state.selected : null;
  const show = keep || (select.value ? select.value.split(".")[0] : ids[0]);
  if (show) showParams(show);
}

// A change of the graph made elsewhere (the file saved by a text editor): reload and cook.
async function poll() {
  try {
    const reply = await api("/api/version");
    if (reply.version !== state.version && !state.cooking && !state.editing) {
      await reload();
      forgetEdits();
      fileChanged($("file").textContent, reply.fileError);
      cook();
    }
  } catch (e) {
    setStatus(`the server does not answer: ${e.message}`, true);
  }
  setTimeout(poll, 1000);
}

$("add").addEventListener("click", () => {
  const type = $("add-type").value;
  let n = 1;
  while (`${type.toLowerCase()}${n}` in state.graph.nodes) ++n;
  const id = `${type.toLowerCase()}${n}`;
  state.selected = id;
  editGraph((g) => { g.nodes[id] = { type }; });
});
$("delete").addEventListener("click", () => {
  const id = state.selected;
  if (!id) return;
  editGraph((g) => {
    delete g.nodes[id];
    for (const n of Object.values(g.nodes))
      for (const [port, source] of Object.entries(n.inputs || {}))
        if (source.split(".")[0] === id) delete n.inputs[port];
  });
});
$("frame").addEventListener("input", () => { $("frame-value").textContent = $("frame").value; });
$("frame").addEventListener("change", cook);
$("preview-node").addEventListener("change", cook);
$("cancel").addEventListener("click", () => api("/api/cancel", {}).catch(() => {}));
$("play").addEventListener("click", () => {
  state.playing = !state.playing;
  $("play").textContent = state.playing ? "Pause" : "Play";
  if (state.playing && !state.cooking) playStep();
});
reload()
  .then(openingFrame)
  .then((frame) => {
    const slider = $("frame");
    if (frame !== null && frame >= Number(slider.min) && frame <= Number(slider.max)) {
      slider.value = frame;
      $("frame-value").textContent = slider.value;
    }
    cook();
    poll();
  })
  .catch((e) => setStatus(e.message, true));
