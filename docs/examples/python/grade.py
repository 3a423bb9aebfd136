"""A node type written in Python, for JSON graphs too:
    cloudgraph run docs/examples/python/graded_cumulus.json \
        --python-nodes docs/examples/python/grade.py"""

import numpy as np

import cloudgraph

REC709_LUMINANCE = np.array([0.2126, 0.7152, 0.0722], dtype=np.float32)


@cloudgraph.node
class Grade:
    """Grades linear radiance: exposure in stops, then saturation around each pixel's
    luminance (Rec. 709 weights). Alpha is kept; the background layer is not passed on."""
    inputs = {"image": cloudgraph.Input("Image", "linear radiance RGBA")}
    outputs = {"image": cloudgraph.Output("Image", "the graded image")}
    params = {
        "exposure": cloudgraph.Param(float, 0.0, min=-10, max=10, units="stops",
                                     doc="radiance is multiplied by 2^exposure"),
        "saturation": cloudgraph.Param(float, 1.0, min=0, max=4,
                                       doc="0: grey, 1: unchanged, above 1: more colour"),
    }

    def cook(self, inputs, params, context):
        image = np.array(inputs["image"])  # (height, width, 4) float32, a writable copy
        rgb = image[..., :3] * np.float32(2.0 ** params["exposure"])
        luminance = (rgb @ REC709_LUMINANCE)[..., None]
        image[..., :3] = luminance + np.float32(params["saturation"]) * (rgb - luminance)
        return {"image": image}
