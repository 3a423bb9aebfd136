// Undo and redo of the page's edits. Each parameter edit and each wiring edit is recorded
// with what it replaced; undoing one sends the old value (or the old graph) to the server as
// a new edit, checked as any edit is, and redoing sends the new one again.
"use strict";

const edits = { done: [], undone: [] };

function showUndoButtons() {
  $("undo").disabled = edits.done.length === 0;
  $("redo").disabled = edits.undone.length === 0;
}

// entry: { kind: "param", node, param, before, after } or { kind: "graph", before, after }.
function recordEdit(entry) {
  edits.done.push(entry);
  edits.undone.length = 0;
  showUndoButtons();
}

// Moves the last entry of `from` to `to`, applying its `side` ("before" or "after").
async function replayEdit(from, to, side) {
  const entry = from.pop();
  if (!entry) return;
  const ok = entry.kind === "param"
    ? await sendParam(entry.node, entry.param, entry[side])
    : await sendGraph(entry[side]);
  (ok ? to : from).push(entry);
  showUndoButtons();
  if (!ok) return;
  if (entry.kind === "param" && state.selected === entry.node) showParams(entry.node);
  cook();
}

// The graph was replaced from its file (changed on disk): the recorded edits refer to a graph
// that is gone, so none can be undone or redone.
function forgetEdits() {
  edits.done.length = 0;
  edits.undone.length = 0;
  showUndoButtons();
}

const undoEdit = () => replayEdit(edits.done, edits.undone, "before");
const redoEdit = () => replayEdit(edits.undone, edits.done, "after");

$("undo").addEventListener("click", undoEdit);
$("redo").addEventListener("click", redoEdit);
// Ctrl+Z / Ctrl+Shift+Z / Ctrl+Y (Cmd on a Mac), except while typing in a field, where the
// field's own undo applies.
document.addEventListener("keydown", (e) => {
  if (!(e.ctrlKey || e.metaKey) || ["INPUT", "SELECT", "TEXTAREA"].includes(e.target.tagName))
    return;
  const key = e.key.toLowerCase();
  if (key === "z" && !e.shiftKey) undoEdit();
  else if (key === "y" || (key === "z" && e.shiftKey)) redoEdit();
  else return;
  e.preventDefault();
});
