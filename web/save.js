// Save, and the file on disk changing under the page. Save refuses (409, conflict) to
// replace a file that changed since the page loaded or saved it: the dialog says so and
// lets the user reload the file (dropping the page's edits) or overwrite it. When the file
// changes on disk while the page has unsaved edits, the server loads it and the page shows
// it: a notice says that those edits were replaced, so they are never lost unseen.
"use strict";

const saving = {
  unsaved: false,  // the page edited the graph since it was loaded, reloaded or saved
};

// Called by the panels after each edit the server accepted.
function markEdited() {
  saving.unsaved = true;
}

function showNotice(text) {
  $("notice-text").textContent = text;
  $("notice").hidden = false;
}

// The graph changed outside the page and the page has just shown the server's graph:
// `fileError` is why the file did not load (then the server kept the page's graph).
function fileChanged(file, fileError) {
  if (fileError) return;  // the page's edits are still the graph; reload() says why
  if (saving.unsaved)
    showNotice(`${file} changed on disk: your unsaved edits were replaced by its version.`);
  saving.unsaved = false;
}

async function save(overwrite) {
  $("conflict").close();
  try {
    const reply = await api("/api/save", overwrite ? { overwrite: true } : {});
    saving.unsaved = false;
    setStatus(`saved ${reply.saved}`);
  } catch (e) {
    if (!e.conflict) {
      setStatus(e.message, true);
      return;
    }
    $("conflict-text").textContent = e.message;
    setStatus("not saved: the file changed on disk", true);
    $("conflict").showModal();
  }
}

// The file as it is on disk, in place of the page's edits; a file that does not load cannot
// be shown, so the dialog stays with the loader's message.
async function reloadFromDisk() {
  const { fileError } = await api("/api/version");
  if (fileError) {
    $("conflict-text").textContent = `The file on disk does not load, so the page cannot ` +
      `show it: ${fileError}. Fix it in your editor, or overwrite it with the page's graph.`;
    return;
  }
  $("conflict").close();
  saving.unsaved = false;
  await reload();
  cook();
}

$("save").addEventListener("click", () => save(false));
$("conflict-overwrite").addEventListener("click", () => save(true));
$("conflict-reload").addEventListener("click", () =>
  reloadFromDisk().catch((e) => setStatus(e.message, true)));
$("conflict-cancel").addEventListener("click", () => $("conflict").close());
$("notice-close").addEventListener("click", () => { $("notice").hidden = true; });
