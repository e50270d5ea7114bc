"""The render passes the post tree reads: turned on in the one view layer the tree reads, only
those, in the engine the scene renders with.

The passes Sandscape turned on are recorded on its tree and turned off again when no effect
reads them any more (or the tree goes); a pass the artist had on is never turned off.
"""

CYCLES, EEVEE = "CYCLES", "BLENDER_EEVEE"
ENGINE_NAMES = {CYCLES: "Cycles", EEVEE: "EEVEE"}
RECORD = "passes_turned_on"  # on our tree: "layer|owner|property" per pass we turned on, ";"-joined
AOV = "aov"  # the owner recorded for the glint AOV we added

# (label, owner path on the view layer, property)
ENVIRONMENT = ("Environment", "", "use_pass_environment")
CYCLES_VOLUME = (("Volume Direct", "cycles", "use_pass_volume_direct"),
                 ("Volume Indirect", "cycles", "use_pass_volume_indirect"))
EEVEE_VOLUME = (("Volume Light", "eevee", "use_pass_volume_direct"),)
GLINT_PASSES = (("Denoising Data", "cycles", "denoising_store_passes"),
                ("Glossy Direct", "", "use_pass_glossy_direct"),
                ("Glossy Indirect", "", "use_pass_glossy_indirect"),
                ("Glossy Color", "", "use_pass_glossy_color"),
                ("Emission", "", "use_pass_emit"))
LABELS = {(owner, prop): label for label, owner, prop in (ENVIRONMENT, *CYCLES_VOLUME, *EEVEE_VOLUME,
                                                          *GLINT_PASSES)}


def denoises(settings, engine):
    """The tree denoises all but the glints only in Cycles: the passes it needs are Cycles'."""
    return bool(settings.use_denoise) and engine == CYCLES


def needed(settings, engine):
    """(label, owner, property) of each pass the tree reads for these settings in this engine."""
    wanted = []
    if settings.use_god_rays or settings.use_blur:
        wanted.append(ENVIRONMENT)  # where the sky is seen: the rays' source and the blur's guide
    if settings.use_blur:
        wanted.extend(CYCLES_VOLUME if engine == CYCLES else EEVEE_VOLUME)
    if denoises(settings, engine):
        wanted.extend(GLINT_PASSES)
    return wanted


def update(tree, scene, layer, settings, engine, aov_name):
    """Turn on in `layer` what the tree reads, and off what Sandscape turned on before that
    nothing reads now (settings None: nothing). Returns (labels turned on, labels turned off)."""
    record = _read(tree)
    wanted = needed(settings, engine) if settings is not None else []
    turned_on, turned_off = [], []
    for label, owner, prop in wanted:
        holder = _holder(layer, owner)
        if not getattr(holder, prop):
            setattr(holder, prop, True)
            record.add((layer.name, owner, prop))
            turned_on.append(label)
    if settings is not None and denoises(settings, engine) and layer.aovs.get(aov_name) is None:
        layer.aovs.add().name = aov_name
        record.add((layer.name, AOV, aov_name))
        turned_on.append(f"AOV '{aov_name}'")
    if settings is not None and denoises(settings, engine):
        layer.aovs[aov_name].type = "VALUE"
    keep = {(layer.name, owner, prop) for _, owner, prop in wanted}
    if settings is not None and denoises(settings, engine):
        keep.add((layer.name, AOV, aov_name))
    for entry in sorted(record - keep):
        name, owner, prop = entry
        record.discard(entry)
        target = scene.view_layers.get(name)
        if target is None:
            continue
        if owner == AOV:
            aov = target.aovs.get(prop)
            if aov is not None:
                target.aovs.remove(aov)
                turned_off.append(f"AOV '{prop}'")
        elif getattr(_holder(target, owner), prop):
            setattr(_holder(target, owner), prop, False)
            turned_off.append(LABELS.get((owner, prop), prop))
    tree[RECORD] = ";".join("|".join(entry) for entry in sorted(record))
    return turned_on, turned_off


def _holder(layer, owner):
    return getattr(layer, owner) if owner else layer


def _read(tree):
    text = tree.get(RECORD, "")
    return {tuple(item.split("|")) for item in text.split(";") if item.count("|") == 2}
