// The page of `cloudgraph serve`: the network, the selected node's parameters (widgets made
// from the node declarations, every edit checked by the server as the CLI checks it), the
// preview of a renderer at the current frame, recooked after each edit, and the cook report.
"use strict";

const state = {
  graph: null,        // the graph's JSON, as the server has it
  types: {},          // declarations of the node types in the graph
  groups: {},         // the network's SVG group of each node
  selected: null,     // the node whose parameters are shown
  cooking: false,
  again: false,       // an edit came during a cook: cook once more when it ends
  playing: false,
};
const $ = (id) => document.getElementById(id);

function setStatus(text, isError = false) {
  $("status").textContent = text;
  $("status").classList.toggle("error", isError);
}

async function api(path, body) {
  const options = body === undefined ? {} :
    { method: "POST", headers: { "Content-Type": "application/json" }, body: JSON.stringify(body) };
  const response = await fetch(path, options);
  const reply = await response.json();
  if (!response.ok) throw new Error(reply.error || response.statusText);
  return reply;
}

// Renderers (nodes with an Image output) the preview can show.
function imageOutputs() {
  const found = [];
  for (const [id, node] of Object.entries(state.graph.nodes)) {
    const port = state.types[node.type].outputs.find((p) => p.type === "Image");
    if (port) found.push({ id, port: port.name });
  }
  return found;
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
      inputs.push(input);
      read = () => Number(input.value);
    } else if (p.type === "vec3") {
      for (const v of value) inputs.push(numberInput(v, false));
      read = () => inputs.map((i) => Number(i.value));
    } else if (p.type === "string") {
      const input = document.createElement("input");
      input.value = value;
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
    label.appendChild(editor);
    form.appendChild(label);
    form.appendChild(message);
  }
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
  try {
    await api("/api/param", { node: id, param: name, value });
  } catch (e) {
    message.textContent = e.message;   // the CLI's own message, naming node and parameter
    setStatus(e.message, true);
    return;
  }
  (state.graph.nodes[id].params ||= {})[name] = value;
  setStatus(`${id}.${name} = ${JSON.stringify(value)}`);
  cook();
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
  $("cancel").disabled = false;
  const [node, port] = choice.split(".");
  state.groups[node]?.classList.add("cooking");
  setStatus(`cooking ${node} at frame ${$("frame").value}…`);
  try {
    const reply = await api("/api/cook", { node, port, frame: Number($("frame").value) });
    showReport(reply.report, reply.seconds);
    if (reply.preview) $("preview").src = `${reply.preview}&t=${Date.now()}`;
  } catch (e) {
    setStatus(e.message, true);
  } finally {
    state.cooking = false;
    document.body.dataset.cooks = Number(document.body.dataset.cooks || 0) + 1;  // for tests
    $("cancel").disabled = true;
    state.groups[node]?.classList.remove("cooking");
  }
  if (state.again) {
    state.again = false;
    cook();
  } else if (state.playing) {
    nextFrame();
  }
}

function nextFrame() {
  const slider = $("frame");
  const next = Number(slider.value) + 1;
  slider.value = next > Number(slider.max) ? slider.min : next;
  $("frame-value").textContent = slider.value;
  cook();
}

async function load() {
  const reply = await api("/api/graph");
  state.graph = reply.graph;
  state.types = reply.types;
  $("file").textContent = reply.file;
  const frames = state.graph.frames;
  const slider = $("frame");
  slider.min = frames.start;
  slider.max = frames.end;
  slider.value = frames.start;
  $("frame-value").textContent = slider.value;
  state.groups = drawNetwork($("network"), state.graph.nodes, state.types, showParams);
  const select = $("preview-node");
  select.replaceChildren();
  for (const { id, port } of imageOutputs()) select.add(new Option(id, `${id}.${port}`));
  const first = Object.keys(state.graph.nodes).sort()[0];
  if (first) showParams(select.value ? select.value.split(".")[0] : first);
}

$("frame").addEventListener("input", () => { $("frame-value").textContent = $("frame").value; });
$("frame").addEventListener("change", cook);
$("preview-node").addEventListener("change", cook);
$("cancel").addEventListener("click", () => api("/api/cancel", {}).catch(() => {}));
$("play").addEventListener("click", () => {
  state.playing = !state.playing;
  $("play").textContent = state.playing ? "Pause" : "Play";
  if (state.playing && !state.cooking) nextFrame();
});
$("save").addEventListener("click", async () => {
  try {
    const reply = await api("/api/save", {});
    setStatus(`saved ${reply.saved}`);
  } catch (e) {
    setStatus(e.message, true);
  }
});
load().then(cook).catch((e) => setStatus(e.message, true));
