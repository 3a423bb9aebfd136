"""`cloudgraph serve`'s page in headless Chromium, driven as a user drives it: Figure 6 at a
reduced size, the sun moved, only the Renderer and its writer recook (the page's own cook
report), the
preview changes, a long cook shows its progress, an out-of-range value is refused naming node and parameter, and the saved
graph loads in the CLI with the edit; Save refuses to replace a file changed on disk and offers
to overwrite it, and a change on disk that replaces unsaved edits is said. Optionally saves a
screenshot of the page."""

import argparse
import difflib
import json
import math
import os
import re
import shutil
import subprocess
import sys
import urllib.request
import zlib

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from webdriver import Browser  # noqa: E402

PREVIEW_BYTES = """
const img = document.getElementById('preview');
return fetch(img.src).then(r => r.arrayBuffer()).then(b => {
  const bytes = new Uint8Array(b);
  let h = 0;
  for (const x of bytes) h = (h * 31 + x) >>> 0;
  return bytes.length + ':' + h;
});"""
PROGRESS_SHOWN = """const row = document.getElementById('progress-row');
return getComputedStyle(row).display !== 'none' &&
       document.getElementById('progress-text').textContent;"""
DRAG = """
const [fromSelector, toSelector] = arguments;
const from = document.querySelector(fromSelector);
const to = toSelector ? document.querySelector(toSelector) : document.getElementById('network');
from.dispatchEvent(new PointerEvent('pointerdown', {bubbles: true}));
to.dispatchEvent(new PointerEvent('pointermove', {bubbles: true}));
to.dispatchEvent(new PointerEvent('pointerup', {bubbles: true}));"""
WIRE = "return !!document.querySelector('[data-wire=\"voxelize.volume->render.volume\"]');"
COOKS = "return Number(document.body.dataset.cooks || 0);"
# A left-button drag across the preview from x = arguments[0] to arguments[1] (px), 30 px
# from its top.
POINTER_DRAG = """const img = document.getElementById('preview');
const r = img.getBoundingClientRect();
const at = (type, x) => img.dispatchEvent(new PointerEvent(type, {bubbles: true, button: 0,
    pointerId: 1, clientX: r.left + x, clientY: r.top + 30}));
at('pointerdown', arguments[0]); at('pointermove', arguments[1]); at('pointerup', arguments[1]);"""
# arguments[0] wheel notches away from the scene on the preview.
WHEEL = """const img = document.getElementById('preview');
for (let i = 0; i < arguments[0]; ++i)
  img.dispatchEvent(new WheelEvent('wheel', {bubbles: true, cancelable: true, deltaY: 100}));"""
STATUS = "return document.getElementById('status').textContent;"
# The render node's box on the page: [left, top, width, height].
RENDER_BOX = """const r = document.querySelector('g[data-node="render"] rect.body')
                    .getBoundingClientRect();
return [r.left, r.top, r.width, r.height];"""
# A left-button drag in the network from (x, y) by (dx, dy), page pixels, starting on the
# element `arguments[0]` (the svg for its background).
NET_DRAG = """const [selector, x, y, dx, dy] = arguments;
const svg = document.getElementById('network');
const on = document.querySelector(selector);
const at = (el, type, px, py) => el.dispatchEvent(new PointerEvent(type, {bubbles: true,
    button: 0, pointerId: 2, clientX: px, clientY: py}));
at(on, 'pointerdown', x, y); at(svg, 'pointermove', x + dx / 2, y + dy / 2);
at(svg, 'pointermove', x + dx, y + dy); at(svg, 'pointerup', x + dx, y + dy);"""
# A stroke on the paint canvas from x = arguments[0] to arguments[1] (shares of its width)
# at the height arguments[2] (share of its height).
PAINT_STROKE = """const [x0, x1, y] = arguments;
const c = document.getElementById('paint-canvas');
const r = c.getBoundingClientRect();
const at = (type, x) => c.dispatchEvent(new PointerEvent(type, {bubbles: true, button: 0,
    pointerId: 3, clientX: r.left + x * r.width, clientY: r.top + y * r.height}));
at('pointerdown', x0); at('pointermove', (x0 + x1) / 2); at('pointermove', x1);
at('pointerup', x1);"""
NET_WHEEL = """const [x, y, deltaY] = arguments;
document.getElementById('network').dispatchEvent(new WheelEvent('wheel',
    {bubbles: true, cancelable: true, clientX: x, clientY: y, deltaY}));"""
REPORT = """return [...document.querySelectorAll('#report tbody tr')]
                .map(r => [r.dataset.node, r.dataset.status]);"""
SET_INPUTS = """
const [param, values] = arguments;
const inputs = [...document.querySelectorAll(
  `#params [data-param="${param}"]:not([type="range"])`)];
inputs.forEach((input, i) => { input.value = values[i]; });
inputs[0].dispatchEvent(new Event('change'));
return inputs.length;"""

SLIDE = """
const [param, value] = arguments;
const slider = document.querySelector(`#params input[type="range"][data-param="${param}"]`);
if (!slider) return false;
slider.value = value;
slider.dispatchEvent(new Event('input'));
slider.dispatchEvent(new Event('change'));
return true;"""
PICK = """
const [param, hex] = arguments;
const picker = document.querySelector(`#params input[type="color"][data-colour="${param}"]`);
if (!picker) return false;
picker.value = hex;
picker.dispatchEvent(new Event('change'));
return true;"""
PARAM = """const node = state.graph.nodes.render;
const decl = state.types[node.type].params.find((p) => p.name === arguments[0]);
return JSON.stringify(paramValue('render', decl));"""
FOV_BOX = """return document.querySelector('#params input[type="number"][data-param="fov"]').value;"""


CONFLICT_SHOWN = """return document.getElementById('conflict').open &&
                          document.getElementById('conflict-text').textContent;"""


def png_pixels(data):
    """(width, height, channels, rows of bytes) of an 8-bit grey, RGB or RGBA PNG, unfiltered."""
    assert data[:8] == b"\x89PNG\r\n\x1a\n", "not a PNG"
    at, idat, header = 8, b"", None
    while at < len(data):
        length = int.from_bytes(data[at:at + 4], "big")
        kind, body = data[at + 4:at + 8], data[at + 8:at + 8 + length]
        if kind == b"IHDR":
            header = body
        elif kind == b"IDAT":
            idat += body
        at += 12 + length
    width, height = int.from_bytes(header[0:4], "big"), int.from_bytes(header[4:8], "big")
    assert header[8] == 8 and header[12] == 0, "only 8-bit, non-interlaced PNGs"
    channels = {0: 1, 2: 3, 6: 4}[header[9]]
    raw, stride, rows, previous = zlib.decompress(idat), width * channels, [], bytes(width * channels)
    for y in range(height):
        kind, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - channels] if i >= channels else 0
            b, c = previous[i], previous[i - channels] if i >= channels else 0
            if kind == 1:
                line[i] = (line[i] + a) & 255
            elif kind == 2:
                line[i] = (line[i] + b) & 255
            elif kind == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif kind == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(bytes(line))
        previous = line
    return width, height, channels, rows


def replace_file(path, text):
    """Replaces `path` by `text` as an editor saves: a new file renamed over it."""
    with open(path + ".new", "w") as f:
        f.write(text)
    os.replace(path + ".new", path)


def small_figure6(source, target):
    """Figure 6 as the golden tests shrink it: the small primitive, coarser voxels, a
    thumbnail render, frames up to 160."""
    with open(source) as f:
        graph = json.load(f)
    graph["frames"]["end"] = 160
    nodes = graph["nodes"]
    nodes["primitive"]["params"] = {"frames": 40, "width": 400.0, "height": 700.0,
                                    "sourceHeight": 100.0, "sourceRadius": 125.0,
                                    "sourceHumidity": 1.0}
    nodes["voxelize"]["params"]["voxelSize"] = 80
    nodes["render"]["params"].update({"width": 160, "height": 120})
    nodes["video"]["params"]["lastFrame"] = 160
    with open(target, "w") as f:
        json.dump(graph, f, indent=1)


def wait_for_cook(browser, cooks_before, what):
    """Waits for a cook after `cooks_before`, and for the page to be idle (an edit during a
    cook cancels it and cooks again: the last one is the one that counts)."""
    browser.wait_for(f"return Number(document.body.dataset.cooks || 0) > {cooks_before} &&"
                     " document.body.dataset.cooking === undefined;", timeout=300)
    status = browser.run(STATUS)
    assert status.startswith("cooked frame"), f"{what}: the cook failed: {status}"


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--cloudgraph", required=True)
    ap.add_argument("--graph", required=True)
    ap.add_argument("--work", required=True)
    ap.add_argument("--chromium", required=True)
    ap.add_argument("--chromedriver", required=True)
    ap.add_argument("--screenshot", help="save a PNG of the page here")
    args = ap.parse_args()

    shutil.rmtree(args.work, ignore_errors=True)
    os.makedirs(os.path.join(args.work, "out"))
    graph_file = os.path.join(args.work, "figure6_small.json")
    small_figure6(args.graph, graph_file)

    server = subprocess.Popen(
        [args.cloudgraph, "serve", graph_file, "--port", "0",
         "--out", os.path.join(args.work, "out"), "--cache", os.path.join(args.work, "cache")],
        stdout=subprocess.PIPE, text=True)
    browser = None
    try:
        line = server.stdout.readline()
        url = line.split(" at ")[1].split(" ")[0]
        browser = Browser(args.chromium, args.chromedriver, os.path.join(args.work, "profile"))
        # Opened plainly, the page finds the last frame with a cloud (the end, 160, for this
        # graph, whose cloud only grows) and cooks it.
        browser.open(url)
        wait_for_cook(browser, 0, "the first cook")
        opened = browser.run("return document.getElementById('frame').value;")
        assert opened == "160", f"the page opened on frame {opened}, not the last with a cloud"
        # The rest starts from frame 0, as the address asks.
        browser.open(url + ("&" if "?" in url else "?") + "frame=0")
        wait_for_cook(browser, 0, "the cook at frame 0")
        assert browser.run("return document.getElementById('frame').value;") == "0"

        # A long cook shows its progress while it runs: the path tracer, on a frame with a
        # cloud (every node upstream cooks once), then the fast mode again.
        browser.run("""document.querySelector('g[data-node="render"]')
                         .dispatchEvent(new MouseEvent('click', {bubbles: true}));""")
        cooks = browser.run(COOKS)
        browser.run(SET_INPUTS, "mode", ["pathtrace"])
        wait_for_cook(browser, cooks, "the path tracer at frame 0")
        cooks = browser.run(COOKS)
        browser.run("""const s = document.getElementById('frame'); s.value = 150;
                       s.dispatchEvent(new Event('input'));
                       s.dispatchEvent(new Event('change'));""")
        progress = browser.wait_for(PROGRESS_SHOWN, timeout=120)
        assert re.fullmatch(r"\d+ / \d+ · \d+\.\d s", progress), progress
        wait_for_cook(browser, cooks, "frame 150")
        assert not browser.run(PROGRESS_SHOWN), "the progress bar stayed after the cook"
        cooks = browser.run(COOKS)
        browser.run(SET_INPUTS, "mode", ["fast"])
        wait_for_cook(browser, cooks, "the fast mode at frame 150")
        before = browser.run(PREVIEW_BYTES)

        # Move the sun, with the Renderer's writers writing.
        browser.run("document.getElementById('write').checked = true;")
        title = browser.run("return document.getElementById('params-title').textContent;")
        assert title.startswith("render"), title
        cooks = browser.run(COOKS)
        assert browser.run(SET_INPUTS, "sunDirection", [0.8, -1, 0.5]) == 3
        wait_for_cook(browser, cooks, "the sun edit")
        report = dict(browser.run(REPORT))
        assert report.get("render") == "cooked", report
        recooked = sorted(n for n, s in report.items() if s == "cooked")
        assert recooked == ["camera", "image", "render", "shot"], \
            f"only the Renderer and its writers should recook: {report}"
        frame_file = os.path.join(args.work, "out", "figure6", "frame.0150.png")
        assert os.path.exists(frame_file), "the writer wrote no frame"
        assert browser.run(PREVIEW_BYTES) != before, "the preview did not change"

        # An out-of-range value: refused with the node and parameter named.
        browser.run(SET_INPUTS, "width", [0])
        error = browser.wait_for("""return [...document.querySelectorAll('#params .error')]
                                     .map(e => e.textContent).join('');""", timeout=30)
        assert "/nodes/render/params/width" in error and "minimum" in error, error

        cooks = browser.run(COOKS)
        browser.run(SET_INPUTS, "width", [160])
        wait_for_cook(browser, cooks, "width back to 160")

        # A bounded number has a slider beside its box, and a colour a picker: each edit goes
        # through as a typed one does; undo sends the old values back, redo the new ones.
        fov_before = browser.run(PARAM, "fov")
        colour_before = browser.run(PARAM, "sunColour")
        cooks = browser.run(COOKS)
        assert browser.run(SLIDE, "fov", 50), "fov has no slider"
        wait_for_cook(browser, cooks, "the fov slider")
        assert browser.run(PARAM, "fov") == "50", browser.run(PARAM, "fov")
        assert browser.run(FOV_BOX) == "50", browser.run(FOV_BOX)
        assert not browser.run(SLIDE, "width", 100), "a 1-4096 px width got a slider"
        cooks = browser.run(COOKS)
        assert browser.run(PICK, "sunColour", "#808080"), "sunColour has no picker"
        wait_for_cook(browser, cooks, "the sun colour picker")
        # sRGB 128/255 is linear 0.2158605.
        assert json.loads(browser.run(PARAM, "sunColour")) == [0.2159] * 3, \
            browser.run(PARAM, "sunColour")
        for expected_fov, expected_colour, button in (
                ("50", colour_before, "undo"), (fov_before, colour_before, "undo"),
                ("50", colour_before, "redo")):
            cooks = browser.run(COOKS)
            browser.run(f"document.getElementById('{button}').click();")
            wait_for_cook(browser, cooks, button)
            assert browser.run(PARAM, "fov") == expected_fov, (button, browser.run(PARAM, "fov"))
            assert browser.run(PARAM, "sunColour") == expected_colour, button
        # Orbit: a drag of 40 px to the right on the preview turns the camera 16 degrees
        # clockwise seen from above about the look-at point, at the same distance and
        # height; two wheel notches away move it 1.1^2 as far; Undo takes the dolly back.
        def camera():
            return json.loads(browser.run(PARAM, "cameraPosition"))
        look_at = [3200, 3200, 4000]
        start = camera()
        cooks = browser.run(COOKS)
        browser.run(POINTER_DRAG, 50, 90)
        wait_for_cook(browser, cooks, "the orbit")
        turned = camera()
        rel0 = [a - b for a, b in zip(start, look_at)]
        rel1 = [a - b for a, b in zip(turned, look_at)]
        turn = math.degrees(math.atan2(rel1[1], rel1[0]) - math.atan2(rel0[1], rel0[0]))
        assert abs(turn + 16) < 0.05, f"turned {turn} degrees, not -16"
        assert abs(math.dist(turned, look_at) - math.dist(start, look_at)) < 0.2
        assert abs(rel1[2] - rel0[2]) < 0.1, (start, turned)
        cooks = browser.run(COOKS)
        browser.run(WHEEL, 2)
        wait_for_cook(browser, cooks, "the dolly")
        dollied = camera()
        assert abs(math.dist(dollied, look_at) / math.dist(turned, look_at) - 1.21) < 1e-3, \
            (turned, dollied)
        cooks = browser.run(COOKS)
        browser.run("document.getElementById('undo').click();")
        wait_for_cook(browser, cooks, "undo of the dolly")
        assert camera() == turned, (camera(), turned)
        # A keyed camera: the drag moves the key at the slider's frame (150).
        key = [150, 3200, -6500, 2000, 3200, 3200, 4000, 45]
        browser.run("sendParam('render', 'cameraKeys', arguments[0]);", key)
        browser.wait_for("return (state.graph.nodes.render.params.cameraKeys || []).length === 8;",
                         timeout=30)
        cooks = browser.run(COOKS)
        browser.run(POINTER_DRAG, 50, 90)
        wait_for_cook(browser, cooks, "the orbit of a key")
        moved = json.loads(browser.run(PARAM, "cameraKeys"))
        assert moved[0] == 150 and moved[4:] == key[4:], moved
        rel = [a - b for a, b in zip(moved[1:4], look_at)]
        turn = math.degrees(math.atan2(rel[1], rel[0]) - math.atan2(key[2] - 3200, key[1] - 3200))
        assert abs(turn + 16) < 0.05, f"the key turned {turn} degrees, not -16"
        browser.run("sendParam('render', 'cameraKeys', []);")
        browser.wait_for("return state.graph.nodes.render.params.cameraKeys.length === 0;",
                         timeout=30)
        if args.screenshot:
            browser.screenshot(args.screenshot)

        browser.run("document.getElementById('save').click();")
        browser.wait_for(f"return document.getElementById('status').textContent"
                         f".startsWith('saved');", timeout=30)
        check = subprocess.run([args.cloudgraph, "validate", graph_file], capture_output=True,
                               text=True)
        assert check.returncode == 0, check.stderr
        with open(graph_file) as f:
            saved = json.load(f)["nodes"]["render"]["params"]
        assert saved["sunDirection"] == [0.8, -1, 0.5], saved
        assert saved["width"] == 160, saved

        # The network: the wheel zooms about the pointer (the point under it stays), a drag
        # of the background pans; neither is an edit of the graph.
        version = browser.run("return state.version;")
        box = browser.run(RENDER_BOX)
        cx, cy = box[0] + box[2] / 2, box[1] + box[3] / 2
        browser.run(NET_WHEEL, cx + 30, cy, -100)
        zoomed = browser.run(RENDER_BOX)
        assert abs(zoomed[2] / box[2] - 1.1) < 1e-3, (box, zoomed)
        assert abs(zoomed[0] - (cx + 30 - (cx + 30 - box[0]) * 1.1)) < 0.5, (box, zoomed)
        browser.run(NET_DRAG, "#network", 5, 5, 30, 20)
        panned = browser.run(RENDER_BOX)
        assert abs(panned[0] - zoomed[0] - 30) < 0.5 and abs(panned[1] - zoomed[1] - 20) < 0.5
        assert browser.run("return state.version;") == version, "pan or zoom edited the graph"
        # Dragging a node moves it: one edit of its position (network units, the drag over
        # the zoom), undoable, and Save writes that line alone.
        with open(graph_file) as f:
            saved_text = f.read()
        start = browser.run("return [network.boxes.render.x, network.boxes.render.y];")
        scale = browser.run("return netView.scale;")
        browser.run(NET_DRAG, 'g[data-node="render"] rect.body', panned[0] + 20, panned[1] + 10,
                    44, 22)
        moved_to = [round(start[0] + 44 / scale), round(start[1] + 22 / scale)]
        browser.wait_for(f"return JSON.stringify(state.graph.nodes.render.position) === "
                         f"'{json.dumps(moved_to, separators=(',', ':'))}';", timeout=30)
        moved = browser.run(RENDER_BOX)
        assert abs(moved[0] - panned[0] - 44) < 0.5 and abs(moved[1] - panned[1] - 22) < 0.5
        browser.run("document.getElementById('save').click();")
        browser.wait_for("return document.getElementById('status').textContent"
                         ".startsWith('saved');", timeout=30)
        with open(graph_file) as f:
            after_text = f.read()
        diff = list(difflib.ndiff(saved_text.splitlines(), after_text.splitlines()))
        added = [line[2:] for line in diff if line.startswith("+ ")]
        removed = [line[2:] for line in diff if line.startswith("- ")]
        assert added == ["      },", f'      "position": [{moved_to[0]}, {moved_to[1]}]'] and \
            removed == ["      }"], (added, removed)
        browser.run("document.getElementById('undo').click();")
        browser.wait_for("return !('position' in state.graph.nodes.render);", timeout=30)
        assert browser.run("return [network.boxes.render.x, network.boxes.render.y];") == start

        # Painting on the noise map's preview: a white stroke across its middle row, used,
        # is a new PNG under out/paintings that a new ReadMap beside the noise reads; the
        # file holds the stroke and, away from it, the noise as the preview showed it.
        cooks = browser.run(COOKS)
        shown = browser.run("return document.getElementById('preview').src;")
        browser.run("""const s = document.getElementById('preview-node'); s.value = 'noise.map';
                       s.dispatchEvent(new Event('change'));""")
        wait_for_cook(browser, cooks, "the noise map's preview")
        # The preview image arrives after the cook: paint only once the map's image is in.
        browser.wait_for("const i = document.getElementById('preview'); return i.src !== "
                         f"{json.dumps(shown)} && i.complete && i.naturalWidth > 0;", timeout=60)
        assert browser.run("return !document.getElementById('paint-row').hidden;"), \
            "no Paint controls on a map's preview"
        browser.run("""const p = document.getElementById('paint'); p.checked = true;
                       p.dispatchEvent(new Event('change'));
                       document.getElementById('brush-value').value = 1;
                       document.getElementById('brush-radius').value = 2;""")
        browser.wait_for("return !document.getElementById('paint-canvas').hidden;", timeout=30)
        size = browser.run("const c = document.getElementById('paint-canvas');"
                           "return [c.width, c.height];")
        browser.run(PAINT_STROKE, 0.2, 0.8, 0.5)
        # The screenshot shows the stroke on the canvas, white across the noise's greys.
        shot = browser.screenshot_png()
        if args.screenshot:
            with open(os.path.splitext(args.screenshot)[0] + "-paint.png", "wb") as f:
                f.write(shot)
        _, _, depth, screen = png_pixels(shot)
        box = browser.run("const r = document.getElementById('paint-canvas')"
                          ".getBoundingClientRect(); return [r.left, r.top, r.width, r.height];")
        row = screen[int(box[1] + 0.5 * box[3])]
        across = [row[depth * int(box[0] + f * box[2])] for f in (0.3, 0.4, 0.5, 0.6, 0.7)]
        assert all(v >= 250 for v in across), f"no white stroke on the screen: {across}"
        below = screen[int(box[1] + 0.75 * box[3])]
        greys = {below[depth * int(box[0] + f / 20 * box[2])] for f in range(1, 20)}
        assert len(greys) > 5, f"the canvas does not show the noise: {greys}"
        cooks = browser.run(COOKS)
        browser.run("document.getElementById('paint-apply').click();")
        browser.wait_for("return state.graph.nodes.paint1 && "
                         "document.getElementById('preview-node').value === 'paint1.map';",
                         timeout=30)
        wait_for_cook(browser, cooks, "the painted map")
        painted_file = os.path.join(args.work, "out", "paintings", "noise.1.png")
        node = browser.run("return state.graph.nodes.paint1;")
        assert node["type"] == "ReadMap" and node["params"]["file"] == \
            os.path.relpath(painted_file, args.work), node
        with open(painted_file, "rb") as f:
            width, height, channels, rows = png_pixels(f.read())
        assert (width, height, channels) == (size[0], size[1], 1), (width, height, channels)
        with urllib.request.urlopen(url.split("?")[0].rstrip("/") +
                                    "/api/preview?node=noise&port=map") as reply:
            _, _, _, noise = png_pixels(reply.read())
        y = int(0.5 * height)
        stroke = [rows[y][x] for x in range(int(0.25 * width), int(0.75 * width))]
        assert all(v == 255 for v in stroke), stroke
        far = [(x, yy) for yy in range(height) if abs(yy + 0.5 - 0.5 * height) > 3
               for x in range(width)]
        assert all(rows[yy][x] == noise[yy][3 * x] for x, yy in far), "the noise was changed"
        assert browser.run(STATUS).startswith("cooked frame"), browser.run(STATUS)
        browser.run("document.getElementById('undo').click();")
        browser.wait_for("return !state.graph.nodes.paint1;", timeout=30)
        browser.run("document.getElementById('save').click();")
        browser.wait_for("return document.getElementById('status').textContent"
                         ".startsWith('saved');", timeout=30)

        # The file edited outside the page (an editor's save): the page reloads it.
        with open(graph_file) as f:
            graph = json.load(f)
        graph["nodes"]["render"]["params"]["fov"] = 33
        with open(graph_file + ".new", "w") as f:
            json.dump(graph, f, indent=1)
        os.replace(graph_file + ".new", graph_file)
        browser.wait_for("""const i = document.querySelector('#params [data-param="fov"]');
                            return i && i.value === '33';""", timeout=30)
        # Its edits refer to a graph that is gone: nothing to undo.
        assert browser.run("return document.getElementById('undo').disabled;"), \
            "undo stayed enabled after the file was reloaded"
        # Wiring by dragging in the network: the Renderer's input picked up and dropped on
        # nothing disconnects it; dragged from the Voxelizer's output onto it, it connects.
        render_input = 'circle[data-node="render"][data-input="volume"]'
        cooks = browser.run(COOKS)
        browser.run(DRAG, render_input, None)
        browser.wait_for(f"return !({WIRE[7:-1]});", timeout=30)
        # Its cook says what is missing, as `cloudgraph run` would.
        browser.wait_for(f"return {COOKS[7:-1]} > {cooks} &&"
                         " document.body.dataset.cooking === undefined;", timeout=60)
        status = browser.run(STATUS)
        assert "/nodes/render/inputs/volume" in status and "not connected" in status, status
        cooks = browser.run(COOKS)
        browser.run(DRAG, 'circle[data-node="voxelize"][data-output="volume"]', render_input)
        browser.wait_for(WIRE, timeout=30)
        wait_for_cook(browser, cooks, "the Renderer wired again")

        # Save refuses to replace a file changed on disk since the page loaded or saved it
        # (here into one that does not load, so the server keeps the page's graph): the
        # dialog says so, and Overwrite saves the page's graph.
        cooks = browser.run(COOKS)
        browser.run(SET_INPUTS, "fov", [35])
        wait_for_cook(browser, cooks, "fov 35")
        replace_file(graph_file, '{"cloudgraph": 1, "nodes": ')
        browser.run("document.getElementById('save').click();")
        conflict = browser.wait_for(CONFLICT_SHOWN, timeout=30)
        assert graph_file in conflict, conflict
        browser.run("document.getElementById('conflict-overwrite').click();")
        browser.wait_for("return document.getElementById('status').textContent"
                         ".startsWith('saved');", timeout=30)
        assert not browser.run(CONFLICT_SHOWN), "the dialog stayed after Overwrite"
        with open(graph_file) as f:
            assert json.load(f)["nodes"]["render"]["params"]["fov"] == 35

        # The file changed on disk while the page has unsaved edits: the page shows the
        # file's graph and says that its edits were replaced.
        cooks = browser.run(COOKS)
        browser.run(SET_INPUTS, "fov", [36])
        wait_for_cook(browser, cooks, "fov 36")
        with open(graph_file) as f:
            graph = json.load(f)
        graph["nodes"]["render"]["params"]["fov"] = 40
        replace_file(graph_file, json.dumps(graph, indent=1))
        notice = browser.wait_for("""const n = document.getElementById('notice');
                                     return !n.hidden && n.textContent;""", timeout=30)
        assert "unsaved edits were replaced" in notice, notice
        browser.wait_for("""const i = document.querySelector('#params [data-param="fov"]');
                            return i && i.value === '40';""", timeout=30)
        # Play shows frames already cooked from the browser's own store, at the fps asked,
        # and cooks only the first it has not seen.
        for f in (41, 42):
            cooks = browser.run(COOKS)
            browser.run(f"""const s = document.getElementById('frame'); s.value = {f};
                            s.dispatchEvent(new Event('change'));""")
            wait_for_cook(browser, cooks, f"frame {f}")
        browser.run("""const s = document.getElementById('frame'); s.value = 40;
                       document.getElementById('fps').value = 10;""")
        cooks = browser.run(COOKS)
        browser.run("document.getElementById('play').click();")
        # Frame 43, the first not kept, is cooked (Play goes on cooking 44, 45, ... until
        # paused, so the page is not idle in between).
        browser.wait_for(f"return {COOKS[7:-1]} > {cooks};", timeout=300)
        browser.run("document.getElementById('play').click();")
        browser.wait_for("return document.body.dataset.cooking === undefined;", timeout=300)
        kept = browser.run("return Number(document.body.dataset.keptShown || 0);")
        assert kept == 2, f"{kept} kept frames shown: frames 41 and 42 should not be cooked"
        assert browser.run(COOKS) >= cooks + 1
        print("the page opened on the last frame with a cloud, played kept frames without"
              " cooking them, orbited and dollied the camera,")
        print("the page loaded, recooked only the Renderer and its writers after the sun edit,"
              " edited fov by its slider and the sun's colour by its picker, undid and redid"
              " them,"
              " showed a long cook's progress, refused width 0, saved a graph the CLI loads,"
              " reloaded the file edited outside it, rewired the Renderer by dragging, offered"
              " to overwrite a file changed on disk, and said when a change on disk replaced"
              " its unsaved edits")
    finally:
        if browser:
            browser.close()
        server.terminate()
        server.wait(timeout=30)


if __name__ == "__main__":
    main()
