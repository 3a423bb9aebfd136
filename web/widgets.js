// Parameter widgets beyond a number box: a slider with typed entry for a number whose range
// a hand can sweep, and a colour picker beside a linear RGB triple. The parameters keep
// their values (linear RGB for colours); the picker shows them in sRGB, as a display does.
"use strict";

// A slider for a bounded number at most 200 units wide (a wider one, such as a time in
// seconds up to 1e6 or an extinction up to 1000 /m, keeps its number box alone).
function wantsSlider(p) {
  return (p.type === "float" || p.type === "int") && p.min !== null && p.max !== null &&
         isFinite(p.min) && isFinite(p.max) && p.max - p.min <= 200;
}

// The slider beside its number box, each following the other as it moves.
function sliderFor(p, box) {
  const slider = document.createElement("input");
  slider.type = "range";
  slider.min = p.min;
  slider.max = p.max;
  slider.step = p.type === "int" ? "1" : "any";
  slider.value = box.value;
  slider.addEventListener("input", () => { box.value = slider.value; });
  box.addEventListener("input", () => { slider.value = box.value; });
  return slider;
}

// A vec3 whose declaration says it is RGB (sun colour, sky, ground albedo).
function isColour(p) {
  return p.type === "vec3" && /\bRGB\b/.test(p.doc || "");
}

function linearToSrgb(v) {
  const c = Math.min(Math.max(v, 0), 1);
  return c <= 0.0031308 ? 12.92 * c : 1.055 * Math.pow(c, 1 / 2.4) - 0.055;
}

function srgbToLinear(s) {
  return s <= 0.04045 ? s / 12.92 : Math.pow((s + 0.055) / 1.055, 2.4);
}

// "#rrggbb" of a linear RGB triple (clamped to [0, 1]), and back to four decimals.
function hexOfLinear(rgb) {
  return "#" + rgb.map((v) => Math.round(linearToSrgb(v) * 255).toString(16).padStart(2, "0"))
    .join("");
}

function linearOfHex(hex) {
  return [1, 3, 5].map((i) =>
    Math.round(srgbToLinear(parseInt(hex.slice(i, i + 2), 16) / 255) * 1e4) / 1e4);
}

// A colour picker for three number boxes (linear RGB): picking fills them and calls `picked`;
// typing in them moves the picker.
function colourPickerFor(boxes, picked) {
  const picker = document.createElement("input");
  picker.type = "color";
  picker.dataset.colour = boxes[0].dataset.param || "";
  const follow = () => { picker.value = hexOfLinear(boxes.map((b) => Number(b.value))); };
  follow();
  for (const box of boxes) box.addEventListener("input", follow);
  picker.addEventListener("change", () => {
    linearOfHex(picker.value).forEach((v, i) => { boxes[i].value = v; });
    picked();
  });
  return picker;
}
