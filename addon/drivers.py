"""Simple-expression drivers: the one way Sandscape makes a value follow the scene without a
handler. Blender evaluates them without Python, so a farm with the extension off and Python
auto-run off renders them the same.

A driver whose target could not be resolved once (a scene without a camera, a deleted sun) is
marked invalid and Blender skips it until the file is reloaded or the driver edited; rearm()
re-enables ours once their targets are there again.
"""

# A lamp's light per colour channel: its energy times its tint, none while it is hidden from renders.
LIGHT_EXPRESSION = "energy * tint * (1 - hidden)"

# The linear value the view shows as white, from a variable `exposure` on the scene's
# view_settings.exposure: what the compositor's effects scale by and threshold against.
WHITE_EXPRESSION = "pow(2, -exposure)"


def drive(owner, path, expression, variables, index=-1):
    """Drive owner.path (index: one element of an array) by a simple expression.

    variables: (name, id_type, id, data_path) each; the driver's old variables are replaced.
    """
    curve = owner.driver_add(path, index) if index >= 0 else owner.driver_add(path)
    driver = curve.driver
    driver.type = "SCRIPTED"
    while driver.variables:
        driver.variables.remove(driver.variables[0])
    for name, id_type, target_id, data_path in variables:
        variable = driver.variables.new()
        variable.name, variable.type = name, "SINGLE_PROP"
        target = variable.targets[0]
        target.id_type, target.id, target.data_path = id_type, target_id, data_path
    driver.expression = expression
    driver.is_valid = True
    return driver


def driven_by(tree, node_name):
    """The ID the first driver on the named node's first input reads (a node tree's), or None."""
    if tree is None or tree.nodes.get(node_name) is None or tree.animation_data is None:
        return None
    path = f'nodes["{node_name}"].inputs[0].default_value'
    driver = next((c.driver for c in tree.animation_data.drivers if c.data_path == path), None)
    return driver.variables[0].targets[0].id if driver is not None and driver.variables else None


def lamp_axis(lamp, names=("sa", "sb", "sc")):
    """Variables reading a lamp's world +Z (matrix_world's third column, towards the sun for a sun
    lamp): names[i] reads component i."""
    return [(name, "OBJECT", lamp, f"matrix_world[2][{row}]") for row, name in enumerate(names)]


def follow_lamp_axis(sockets, lamp):
    """Drive three sockets' values by a lamp's world +Z, one component each (None: no lamp, 0)."""
    names = ("sa", "sb", "sc")
    for socket, name in zip(sockets, names, strict=True):
        if lamp is None:
            socket.driver_remove("default_value")
            socket.default_value = 0.0
        else:
            drive(socket, "default_value", name, lamp_axis(lamp, names))


def follow_lamp_light(sockets, lamp):
    """Drive three sockets' values by a lamp's light, red, green and blue (None: no lamp, 0)."""
    for index, socket in enumerate(sockets):
        if lamp is None:
            socket.driver_remove("default_value")
            socket.default_value = 0.0
        else:
            drive(socket, "default_value", LIGHT_EXPRESSION,
                  [("energy", "OBJECT", lamp, "data.energy"),
                   ("tint", "OBJECT", lamp, f"data.color[{index}]"),
                   ("hidden", "OBJECT", lamp, "hide_render")])


def rearm(animation_data, expressions, ready):
    """Re-enable the invalid drivers of animation_data whose expression is one of ours and whose
    first target `ready(id)` says can be read now. Returns how many."""
    if animation_data is None:
        return 0
    rearmed = 0
    for curve in animation_data.drivers:
        driver = curve.driver
        if driver.is_valid or driver.expression not in expressions or not driver.variables:
            continue
        if not ready(driver.variables[0].targets[0].id):
            continue
        driver.expression = driver.expression  # an edit rebuilds its relations
        driver.is_valid = True
        rearmed += 1
    return rearmed
