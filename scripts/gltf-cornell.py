#!/usr/bin/env python3
"""Writes the embedded Cornell spot scene (assets/cornell-spot: OBJ, MTL and scene.toml) as glTF
2.0, for the glTF loader's tests: assets/gltf/cornell-spot.gltf (+ .bin) and cornell-spot.glb.

The mesh hangs under two nodes whose transforms cancel (a rotation and a translation, then their
inverse), so flattening the hierarchy is tested; the camera and the spot light are nodes with
KHR_lights_punctual, in glTF's photometric units (683 lm/W: 100 W/sr is 68,300 cd); the light
quad's Ke 40 is emissiveFactor 1 with KHR_materials_emissive_strength 40.

Run from the repository root: python3 scripts/gltf-cornell.py
"""
import json
import math
import os
import struct

SRC = "assets/cornell-spot"
OUT = "assets/gltf"


def read_obj(path):
    pos, nrm, groups, mtl = [], [], {}, None
    for line in open(path):
        w = line.split()
        if not w or w[0].startswith("#"):
            continue
        if w[0] == "v":
            pos.append(tuple(float(x) for x in w[1:4]))
        elif w[0] == "vn":
            nrm.append(tuple(float(x) for x in w[1:4]))
        elif w[0] == "usemtl":
            mtl = w[1]
        elif w[0] == "f":
            corners = [tuple(int(i) if i else 0 for i in c.split("/")) for c in w[1:]]
            for k in range(1, len(corners) - 1):
                groups.setdefault(mtl, []).append([corners[0], corners[k], corners[k + 1]])
    return pos, nrm, groups


def read_mtl(path):
    mats, cur = {}, None
    for line in open(path):
        w = line.split()
        if not w or w[0].startswith("#"):
            continue
        if w[0] == "newmtl":
            cur = mats.setdefault(w[1], {"Kd": [0.8] * 3, "Ke": [0.0] * 3, "Ns": 1.0})
        elif w[0] in ("Kd", "Ke"):
            cur[w[0]] = [float(x) for x in w[1:4]]
        elif w[0] == "Ns":
            cur["Ns"] = float(w[1])
    return mats


def main():
    pos, nrm, groups = read_obj(f"{SRC}/cornell.obj")
    mats = read_mtl(f"{SRC}/cornell.mtl")
    blob = bytearray()
    views, accessors, primitives, materials = [], [], [], []

    def add(data, target, count, kind, ctype, lo=None, hi=None):
        while len(blob) % 4:
            blob.append(0)
        views.append({"buffer": 0, "byteOffset": len(blob), "byteLength": len(data), "target": target})
        blob.extend(data)
        acc = {"bufferView": len(views) - 1, "componentType": ctype, "count": count, "type": kind}
        if lo is not None:
            acc["min"], acc["max"] = lo, hi
        accessors.append(acc)
        return len(accessors) - 1

    # Every material of the MTL, used or not (the light quad's emitter is not drawn in this scene,
    # but its emission strength is read).
    index = {}
    for name, m in mats.items():
        # The MTL's Phong exponent as vct maps it (scene::obj): roughness sqrt(2 / (Ns + 2)).
        material = {
            "name": name,
            "pbrMetallicRoughness": {
                "baseColorFactor": m["Kd"] + [1.0],
                "metallicFactor": 0.0,
                "roughnessFactor": math.sqrt(2.0 / (m["Ns"] + 2.0)),
            },
        }
        if max(m["Ke"]) > 0:
            strength = max(m["Ke"])
            material["emissiveFactor"] = [c / strength for c in m["Ke"]]
            material["extensions"] = {"KHR_materials_emissive_strength": {"emissiveStrength": strength}}
        index[name] = len(materials)
        materials.append(material)
    for name, tris in groups.items():
        p, n, idx = [], [], []
        for tri in tris:
            for c in tri:
                idx.append(len(p))
                p.append(pos[c[0] - 1])
                n.append(nrm[c[2] - 1])
        flat_p = [x for v in p for x in v]
        a_pos = add(struct.pack(f"<{len(flat_p)}f", *flat_p), 34962, len(p), "VEC3", 5126,
                    [min(v[i] for v in p) for i in range(3)], [max(v[i] for v in p) for i in range(3)])
        flat_n = [x for v in n for x in v]
        a_nrm = add(struct.pack(f"<{len(flat_n)}f", *flat_n), 34962, len(n), "VEC3", 5126)
        a_idx = add(struct.pack(f"<{len(idx)}H", *idx), 34963, len(idx), "SCALAR", 5123)
        primitives.append({"attributes": {"POSITION": a_pos, "NORMAL": a_nrm}, "indices": a_idx,
                           "material": index[name]})

    # A rotation of 90 degrees about y and a translation, undone by the child node.
    s = math.sqrt(0.5)
    t = [1.0, 2.0, 3.0]
    child_t = [3.0, -2.0, -1.0]  # R^-1 (-t), R^-1 a rotation of -90 degrees about y
    doc = {
        "asset": {"version": "2.0", "generator": "vct scripts/gltf-cornell.py"},
        "extensionsUsed": ["KHR_lights_punctual", "KHR_materials_emissive_strength"],
        "extensions": {"KHR_lights_punctual": {"lights": [{
            "type": "spot", "color": [1.0, 1.0, 1.0], "intensity": 100.0 * 683.0,
            "spot": {"innerConeAngle": math.radians(50.0), "outerConeAngle": math.radians(60.0)},
        }]}},
        "scene": 0,
        "scenes": [{"nodes": [0, 2, 3]}],
        "nodes": [
            {"name": "frame", "translation": t, "rotation": [0.0, s, 0.0, s], "children": [1]},
            {"name": "room", "translation": child_t, "rotation": [0.0, -s, 0.0, s], "mesh": 0},
            {"name": "camera", "translation": [0.0, 2.75, 10.75], "camera": 0},
            {"name": "spot", "translation": [0.0, 5.45, 0.0], "rotation": [-s, 0.0, 0.0, s],
             "extensions": {"KHR_lights_punctual": {"light": 0}}},
        ],
        "cameras": [{"type": "perspective", "perspective": {
            "yfov": math.radians(39.3077), "aspectRatio": 1.0, "znear": 0.05}}],
        "meshes": [{"name": "cornell", "primitives": primitives}],
        "materials": materials,
        "accessors": accessors,
        "bufferViews": views,
    }
    while len(blob) % 4:
        blob.append(0)
    os.makedirs(OUT, exist_ok=True)
    text = dict(doc, buffers=[{"uri": "cornell-spot.bin", "byteLength": len(blob)}])
    with open(f"{OUT}/cornell-spot.gltf", "w") as f:
        json.dump(text, f, indent=1)
    with open(f"{OUT}/cornell-spot.bin", "wb") as f:
        f.write(blob)
    js = json.dumps(dict(doc, buffers=[{"byteLength": len(blob)}])).encode()
    js += b" " * (-len(js) % 4)
    glb = struct.pack("<III", 0x46546C67, 2, 12 + 8 + len(js) + 8 + len(blob))
    glb += struct.pack("<II", len(js), 0x4E4F534A) + js + struct.pack("<II", len(blob), 0x004E4942) + bytes(blob)
    with open(f"{OUT}/cornell-spot.glb", "wb") as f:
        f.write(glb)


if __name__ == "__main__":
    main()
