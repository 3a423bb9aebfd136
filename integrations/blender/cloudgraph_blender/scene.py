"""Builds the Blender scene that matches CloudGraph's Renderer from a run's files: the cloud
volume with its optics, the camera of every frame, the sun, the sky, the ground, the frame
range and motion blur. Each function sets up one thing; `import_run` calls them in order."""

import math
import os

import bpy
import mathutils


def vector(values):
    return mathutils.Vector(values)


def add_volume(sequence, medium, name="CloudGraph cloud"):
    """The VDB sequence as one volume object playing our frame numbers, with a Principled
    Volume: extinction = the grid's value times extinction_per_unit (Blender's Density),
    scattering albedo as the colour, the phase's mean cosine as a single Henyey-Greenstein
    lobe's anisotropy (Cycles has no two-lobe or Mie phase)."""
    first_frame, first_path = sequence[0]
    names = [{"name": os.path.basename(path)} for _, path in sequence]
    result = bpy.ops.object.volume_import(filepath=first_path,
                                          directory=os.path.dirname(first_path), files=names)
    if result != {"FINISHED"}:
        raise RuntimeError("Blender could not import %s: %s" % (first_path, result))
    obj = bpy.context.active_object
    obj.name = name
    volume = obj.data
    volume.frame_start = first_frame  # Blender's frame f shows our frame f
    volume.sequence_mode = "CLIP"  # nothing outside the run's frames with a cloud
    volume.materials.append(cloud_material(medium))
    return obj


def cloud_material(medium):
    material = bpy.data.materials.new("CloudGraph cloud")
    material.use_nodes = True
    nodes = material.node_tree.nodes
    nodes.clear()
    shader = nodes.new("ShaderNodeVolumePrincipled")
    albedo = float(medium["albedo"])
    shader.inputs["Color"].default_value = (albedo, albedo, albedo, 1.0)
    shader.inputs["Density"].default_value = float(medium["extinction_per_unit"])
    shader.inputs["Anisotropy"].default_value = float(medium["mean_cosine"])
    shader.inputs["Absorption Color"].default_value = (0.0, 0.0, 0.0, 1.0)
    output = nodes.new("ShaderNodeOutputMaterial")
    material.node_tree.links.new(shader.outputs["Volume"], output.inputs["Volume"])
    return material


def motion_blur_from(volume_obj, frame_time):
    """Cycles blurs the volume by its `vel` grid (m/s): Unit Second, and the scene's frame
    rate set to the run's (1 / timeStep), so a shutter in frames is that many time steps."""
    volume = volume_obj.data
    volume.grids.load()
    if volume.grids.get("vel") is None:
        return False
    volume.velocity_grid = "vel"
    volume.velocity_unit = "SECOND"
    volume.velocity_scale = 1.0
    scene = bpy.context.scene
    scene.render.fps = 1
    scene.render.fps_base = frame_time  # frames per second = fps / fps_base = 1 / timeStep
    scene.render.use_motion_blur = True
    return True


def camera_basis(position, look_at, up):
    """The camera's world rotation: it looks down its local -z with y up, as CloudGraph's
    pinhole does (right = view x up)."""
    forward = (vector(look_at) - vector(position)).normalized()
    right = forward.cross(vector(up)).normalized()
    true_up = right.cross(forward)
    return mathutils.Matrix((right, true_up, -forward)).transposed()


def add_camera(shot, name="CloudGraph camera"):
    """A camera keyed on every frame of the shot: position, rotation and the vertical field
    of view, on the image's size."""
    data = bpy.data.cameras.new(name)
    data.sensor_fit = "VERTICAL"
    data.clip_start = 1.0
    data.clip_end = 1.0e6  # clouds are kilometres away
    obj = bpy.data.objects.new(name, data)
    bpy.context.scene.collection.objects.link(obj)
    obj.rotation_mode = "QUATERNION"
    for key in shot["camera"]:
        frame = key["frame"]
        obj.location = vector(key["position"])
        obj.rotation_quaternion = camera_basis(key["position"], key["look_at"],
                                               key["up"]).to_quaternion()
        data.angle_y = math.radians(key["vertical_fov_deg"])
        obj.keyframe_insert("location", frame=frame)
        obj.keyframe_insert("rotation_quaternion", frame=frame)
        data.keyframe_insert("lens", frame=frame)
    for curves in (obj.animation_data.action.fcurves, data.animation_data.action.fcurves):
        for curve in curves:
            for point in curve.keyframe_points:
                point.interpolation = "LINEAR"  # every frame is keyed: no overshoot between
    scene = bpy.context.scene
    scene.camera = obj
    scene.render.resolution_x = shot["image"]["width"]
    scene.render.resolution_y = shot["image"]["height"]
    scene.render.resolution_percentage = 100
    scene.render.pixel_aspect_x = scene.render.pixel_aspect_y = 1.0
    return obj


def add_sun(sun, name="CloudGraph sun"):
    """A sun lamp of CloudGraph's irradiance (Blender's Strength is irradiance in W/m^2, as
    ours is in radiance units x sr), shining from `direction` (toward the sun)."""
    data = bpy.data.lights.new(name, "SUN")
    data.energy = float(sun["irradiance"])
    data.color = sun["colour"]
    data.angle = math.radians(0.53)  # the real sun's disc
    obj = bpy.data.objects.new(name, data)
    bpy.context.scene.collection.objects.link(obj)
    obj.rotation_mode = "QUATERNION"
    obj.rotation_quaternion = vector(sun["direction"]).to_track_quat("Z", "Y")
    return obj


def set_sky(sky):
    """The world: CloudGraph's sky, horizon + (zenith - horizon) sqrt(z) above the horizon,
    the horizon's colour below."""
    world = bpy.context.scene.world or bpy.data.worlds.new("CloudGraph sky")
    bpy.context.scene.world = world
    world.use_nodes = True
    nodes, links = world.node_tree.nodes, world.node_tree.links
    nodes.clear()
    direction = nodes.new("ShaderNodeTexCoord")
    split = nodes.new("ShaderNodeSeparateXYZ")
    links.new(direction.outputs["Generated"], split.inputs["Vector"])
    above = nodes.new("ShaderNodeMath")
    above.operation = "MAXIMUM"
    above.inputs[1].default_value = 0.0
    links.new(split.outputs["Z"], above.inputs[0])
    root = nodes.new("ShaderNodeMath")
    root.operation = "SQRT"
    links.new(above.outputs["Value"], root.inputs[0])
    mix = nodes.new("ShaderNodeMixRGB")
    mix.inputs["Color1"].default_value = list(sky["horizon"]) + [1.0]
    mix.inputs["Color2"].default_value = list(sky["zenith"]) + [1.0]
    links.new(root.outputs["Value"], mix.inputs["Fac"])
    background = nodes.new("ShaderNodeBackground")
    links.new(mix.outputs["Color"], background.inputs["Color"])
    output = nodes.new("ShaderNodeOutputWorld")
    links.new(background.outputs["Background"], output.inputs["Surface"])
    return world


def add_ground(ground, size=400000.0, name="CloudGraph ground"):
    """The Lambertian ground z = 0 of the ground's albedo, 400 km across (CloudGraph's is
    infinite; its haze is not reproduced)."""
    if not ground["enabled"]:
        return None
    mesh = bpy.data.meshes.new(name)
    h = size / 2
    mesh.from_pydata([(-h, -h, 0), (h, -h, 0), (h, h, 0), (-h, h, 0)], [], [(0, 1, 2, 3)])
    obj = bpy.data.objects.new(name, mesh)
    bpy.context.scene.collection.objects.link(obj)
    material = bpy.data.materials.new(name)
    material.use_nodes = True
    nodes = material.node_tree.nodes
    nodes.clear()
    diffuse = nodes.new("ShaderNodeBsdfDiffuse")  # roughness 0: Lambertian
    diffuse.inputs["Color"].default_value = list(ground["albedo"]) + [1.0]
    output = nodes.new("ShaderNodeOutputMaterial")
    material.node_tree.links.new(diffuse.outputs["BSDF"], output.inputs["Surface"])
    mesh.materials.append(material)
    return obj


def cycles_for_clouds(scene):
    """Cycles with room for the many scatterings that light a thick cloud's shadowed side
    (Blender's default of 0 volume bounces renders it black)."""
    scene.render.engine = "CYCLES"
    scene.cycles.volume_bounces = 64
    scene.cycles.max_bounces = max(scene.cycles.max_bounces, 68)


def import_run(sequence, shot, motion_blur=True):
    """Everything above, for one run; returns the objects made."""
    scene = bpy.context.scene
    lighting = shot["lighting"]
    cloud = add_volume(sequence, lighting["medium"])
    camera = add_camera(shot)
    sun = add_sun(lighting["sun"])
    set_sky(lighting["sky"])
    ground = add_ground(lighting["ground"])
    scene.frame_start = shot["frames"]["start"]
    scene.frame_end = shot["frames"]["end"]
    scene.render.fps = 1
    scene.render.fps_base = shot["frame_time_s"]
    cycles_for_clouds(scene)
    blurred = motion_blur and motion_blur_from(cloud, shot["frame_time_s"])
    return {"cloud": cloud, "camera": camera, "sun": sun, "ground": ground,
            "motion_blur": blurred}
