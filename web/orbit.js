// Orbit and dolly the preview's camera with the mouse: dragging on a Renderer's preview turns
// its camera about the look-at point (0.4 degrees a pixel across, 0.3 up and down, the
// elevation kept within 85 degrees of the horizon), the wheel moves it nearer or farther
// (10% a notch). The result is written back as one edit, undoable: the Renderer's
// cameraPosition, or, when the camera is keyed, the position of the key at the current frame.
"use strict";

const ORBIT = { degreesPerPixelX: 0.4, degreesPerPixelY: 0.3, maxElevation: 85, dolly: 1.1 };
const orbit = { drag: null, wheelTimer: null, wheelScale: 1 };

// The Renderer the preview shows, or null.
function previewRenderer() {
  const id = $("preview-node").value.split(".")[0];
  return state.graph?.nodes[id]?.type === "Renderer" ? id : null;
}

function rendererParam(id, name) {
  const decl = state.types.Renderer.params.find((p) => p.name === name);
  return paramValue(id, decl);
}

// Where the camera to move is: {position, lookAt, write(position)}; throws with the reason
// when the camera cannot be moved here.
function cameraToMove(id) {
  if (rendererParam(id, "cameraFile")) throw new Error(`${id}: the camera comes from its cameraFile`);
  const keys = rendererParam(id, "cameraKeys") || [];
  if (!keys.length) {
    return {
      position: rendererParam(id, "cameraPosition"),
      lookAt: rendererParam(id, "cameraLookAt"),
      write: (p) => ({ param: "cameraPosition", value: p }),
    };
  }
  const frame = Number($("frame").value);
  for (let k = 0; k + 8 <= keys.length; k += 8) {
    if (keys[k] !== frame) continue;
    return {
      position: keys.slice(k + 1, k + 4),
      lookAt: keys.slice(k + 4, k + 7),
      write: (p) => {
        const value = keys.slice();
        value.splice(k + 1, 3, ...p);
        return { param: "cameraKeys", value };
      },
    };
  }
  throw new Error(`${id}: the camera is keyed and has no key at frame ${frame}: orbit moves a key at its own frame`);
}

// The position turned by (azimuth, elevation) degrees about lookAt and scaled by `scale`.
function orbitPosition(position, lookAt, azimuth, elevation, scale) {
  const d = position.map((v, i) => v - lookAt[i]);
  const r = Math.hypot(...d);
  const az = Math.atan2(d[1], d[0]) + (azimuth * Math.PI) / 180;
  const limit = (ORBIT.maxElevation * Math.PI) / 180;
  const el = Math.min(Math.max(Math.asin(d[2] / r) + (elevation * Math.PI) / 180, -limit), limit);
  const rr = r * scale;
  const moved = [rr * Math.cos(el) * Math.cos(az), rr * Math.cos(el) * Math.sin(az), rr * Math.sin(el)];
  return moved.map((v, i) => Math.round((lookAt[i] + v) * 10) / 10);
}

// One undoable edit of the camera (as editParam makes), then a cook.
async function moveCamera(id, azimuth, elevation, scale) {
  let camera;
  try {
    camera = cameraToMove(id);
  } catch (e) {
    setStatus(e.message, true);
    return;
  }
  const { param, value } = camera.write(orbitPosition(camera.position, camera.lookAt, azimuth, elevation, scale));
  const before = rendererParam(id, param);
  if (!(await sendParam(id, param, value))) return;
  recordEdit({ kind: "param", node: id, param, before, after: value });
  if (state.selected === id) showParams(id);
  cook();
}

$("preview").addEventListener("pointerdown", (e) => {
  if (!previewRenderer() || e.button !== 0) return;
  orbit.drag = { x: e.clientX, y: e.clientY };
  try {
    $("preview").setPointerCapture(e.pointerId);  // keep the drag when it leaves the picture
  } catch { /* a synthetic pointer has nothing to capture */ }
  e.preventDefault();
});
$("preview").addEventListener("pointermove", (e) => {
  if (!orbit.drag) return;
  const az = -(e.clientX - orbit.drag.x) * ORBIT.degreesPerPixelX;
  const el = (e.clientY - orbit.drag.y) * ORBIT.degreesPerPixelY;
  setStatus(`orbit: ${az.toFixed(1)} degrees around, ${el.toFixed(1)} up (release to render)`);
});
$("preview").addEventListener("pointerup", (e) => {
  const id = previewRenderer();
  const drag = orbit.drag;
  orbit.drag = null;
  if (!drag || !id || (e.clientX === drag.x && e.clientY === drag.y)) return;
  moveCamera(id, -(e.clientX - drag.x) * ORBIT.degreesPerPixelX,
             (e.clientY - drag.y) * ORBIT.degreesPerPixelY, 1);
});
// Wheel notches gathered for a third of a second make one dolly edit.
$("preview").addEventListener("wheel", (e) => {
  const id = previewRenderer();
  if (!id) return;
  e.preventDefault();
  orbit.wheelScale *= e.deltaY > 0 ? ORBIT.dolly : 1 / ORBIT.dolly;
  setStatus(`dolly: distance x ${orbit.wheelScale.toFixed(2)}`);
  clearTimeout(orbit.wheelTimer);
  orbit.wheelTimer = setTimeout(() => {
    const scale = orbit.wheelScale;
    orbit.wheelScale = 1;
    moveCamera(id, 0, 0, scale);
  }, 300);
}, { passive: false });
