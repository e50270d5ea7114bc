"""The render camera's pixel on the glint cells.

Sandscape Glint Cells sizes its cells to a pixel's footprint; these drivers keep the glint
group's Pixel Angle (perspective) and Pixel Size (orthographic) equal to what one pixel of the
scene's active camera spans at the render resolution. They are simple expressions: a farm
evaluates them with Python auto-run off, and they follow a new lens, resolution or camera.
"""

SOCKETS = ("Pixel Angle", "Pixel Size")
# The pixels the camera's angle (or orthographic scale) spans: the larger side when the sensor
# fit is Auto, else the side it names.
_SPAN = "((fit == 0) * max(rx, ry) + (fit == 1) * rx + (fit == 2) * ry) * pct / 100"
EXPRESSIONS = {
    "Pixel Angle": f"(kind == 0) * 2 * tan(angle / 2) / ({_SPAN})",
    "Pixel Size": f"(kind == 1) * ortho / ({_SPAN})",
}
VARIABLES = {  # name -> data path on the scene
    "kind": "camera.data.type", "fit": "camera.data.sensor_fit", "angle": "camera.data.angle",
    "ortho": "camera.data.ortho_scale", "rx": "render.resolution_x", "ry": "render.resolution_y",
    "pct": "render.resolution_percentage",
}


def attach(node, scene):
    """Drive the node's Pixel Angle and Pixel Size from the scene's camera (inputs the artist
    linked are left alone). Returns the number of inputs driven."""
    driven = 0
    for name, expression in EXPRESSIONS.items():
        socket = node.inputs.get(name)
        if socket is None or socket.is_linked:
            continue
        driver = socket.driver_add("default_value").driver
        driver.type = "SCRIPTED"
        while driver.variables:
            driver.variables.remove(driver.variables[0])
        for variable_name, path in VARIABLES.items():
            variable = driver.variables.new()
            variable.name, variable.type = variable_name, "SINGLE_PROP"
            target = variable.targets[0]
            target.id_type, target.id, target.data_path = "SCENE", scene, path
        driver.expression = expression
        driven += 1
    return driven


def pixel_angle(scene):
    """What the Pixel Angle driver gives, in Python (tests and benches)."""
    import math

    camera, render = scene.camera.data, scene.render
    fits = {"AUTO": max(render.resolution_x, render.resolution_y), "HORIZONTAL": render.resolution_x,
            "VERTICAL": render.resolution_y}
    span = fits[camera.sensor_fit] * render.resolution_percentage / 100
    return 2 * math.tan(camera.angle / 2) / span if camera.type == "PERSP" else 0.0
