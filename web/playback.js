// Playback at the speed of the cached frames: every preview the page cooks is kept in the
// browser, by graph version, preview and frame, so that Play shows frames already seen at the
// chosen frames per second and asks the server only for those it has not; an edit (a new
// graph version) starts a fresh set. Also where the page opens: the last frame with a cloud.
"use strict";

const KEPT_FRAMES = 1000;  // previews kept (object URLs of PNGs), the oldest dropped first
const playback = { frames: new Map(), timer: null };

function frameKey(frame) {
  return `${state.version}|${$("preview-node").value}|${frame}`;
}

// Fetches the preview the server made for `frame`, keeps it, and returns its object URL.
async function keepPreview(frame, url) {
  const blob = await (await fetch(url, { cache: "no-store" })).blob();
  const objectUrl = URL.createObjectURL(blob);
  const key = frameKey(frame);
  if (playback.frames.has(key)) URL.revokeObjectURL(playback.frames.get(key));
  playback.frames.delete(key);
  playback.frames.set(key, objectUrl);
  while (playback.frames.size > KEPT_FRAMES) {
    const [oldest, old] = playback.frames.entries().next().value;
    URL.revokeObjectURL(old);
    playback.frames.delete(oldest);
  }
  return objectUrl;
}

// Shows the kept preview of `frame` if there is one.
function showKept(frame) {
  const url = playback.frames.get(frameKey(frame));
  if (!url) return false;
  $("preview").src = url;
  setStatus(`frame ${frame} (kept)`);
  document.body.dataset.keptShown = Number(document.body.dataset.keptShown || 0) + 1;  // tests
  return true;
}

// One step of Play: the next frame, from the kept previews at the chosen rate, else cooked.
function playStep() {
  clearTimeout(playback.timer);
  if (!state.playing || state.cooking) return;
  const slider = $("frame");
  const next = Number(slider.value) + 1;
  slider.value = next > Number(slider.max) ? slider.min : next;
  $("frame-value").textContent = slider.value;
  if (showKept(Number(slider.value))) {
    const fps = Math.min(Math.max(Number($("fps").value) || 24, 1), 60);
    playback.timer = setTimeout(playStep, 1000 / fps);
  } else {
    cook();
  }
}

// The frame the page opens on: ?frame=N in its address, else the last frame whose cloud
// (the cloud particles upstream of the preview) is not empty, else where it is.
async function openingFrame() {
  const asked = new URLSearchParams(location.search).get("frame");
  if (asked !== null) return Number(asked);
  const node = $("preview-node").value.split(".")[0];
  if (!node) return null;
  setStatus("finding the last frame with a cloud…");
  const watching = watchProgress(node);
  try {
    return (await api(`/api/lastcloud?node=${encodeURIComponent(node)}`)).frame;
  } catch (e) {
    setStatus(e.message, true);
    return null;
  } finally {
    state.watching = false;
    await watching;
  }
}
