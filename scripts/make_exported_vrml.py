#!/usr/bin/env python3
"""Writes scenes/vrml/exported.wrl.gz: a world in the style modelling tools export.

What exporters produce and hand-written samples do not: every object a DEF'd Transform with
its pivot (center), rotation and scale, nested as deep as the model's hierarchy (a robot arm,
twelve levels); large IndexedFaceSets with explicit per-vertex normals, texture coordinates and
their own index lists (a 40 x 80 UV globe of 6,240 triangles); materials and meshes shared with
DEF/USE; an image texture; instances repeated with USE; and animation (TimeSensor,
interpolators, ROUTEs) that a still image ignores. Numbers are printed to four decimals, as
exporters do. The output is gzip-compressed, as exporters offer (.wrl.gz).

Usage: scripts/make_exported_vrml.py [output path]
"""
import gzip
import math
import sys

GLOBE_RADIUS = 1.5
GLOBE_RINGS = 40  # latitude bands
GLOBE_SEGMENTS = 80  # longitude bands


def num(v):
    text = f"{v:.4f}".rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text


def vec(*values):
    return " ".join(num(v) for v in values)


def globe(out):
    """A UV sphere as an exporter writes it: shared seam vertices duplicated for texture
    coordinates, triangles at the poles, quads elsewhere, per-vertex normals by index."""
    points, normals, tex = [], [], []
    for i in range(GLOBE_RINGS + 1):
        theta = math.pi * i / GLOBE_RINGS
        for j in range(GLOBE_SEGMENTS + 1):
            phi = 2 * math.pi * j / GLOBE_SEGMENTS
            n = (math.sin(theta) * math.cos(phi), math.cos(theta), -math.sin(theta) * math.sin(phi))
            points.append(tuple(GLOBE_RADIUS * c for c in n))
            normals.append(n)
            tex.append((j / GLOBE_SEGMENTS, 1 - i / GLOBE_RINGS))
    faces = []
    row = GLOBE_SEGMENTS + 1
    for i in range(GLOBE_RINGS):
        for j in range(GLOBE_SEGMENTS):
            a, b = i * row + j, i * row + j + 1
            c, d = (i + 1) * row + j + 1, (i + 1) * row + j
            if i == 0:
                faces.append((a, d, c))  # the north pole: one corner
            elif i == GLOBE_RINGS - 1:
                faces.append((a, d, b))  # the south pole
            else:
                faces.append((a, d, c, b))
    indices = " ".join(" ".join(str(k) for k in f) + " -1," for f in faces)
    out.append(f"""DEF Globe Transform {{
  translation 0 {num(GLOBE_RADIUS)} 0
  rotation 0 1 0 0.4
  children [
    Shape {{
      appearance Appearance {{
        material DEF Paint-MAT Material {{
          diffuseColor 0.8 0.8 0.8
          ambientIntensity 0.3
          specularColor 0.3 0.3 0.3
          shininess 0.2
          transparency 0
        }}
        texture ImageTexture {{ url "textures/gradient.bmp" }}
      }}
      geometry DEF Globe-FACES IndexedFaceSet {{
        ccw TRUE
        solid TRUE
        creaseAngle 1.5
        coord DEF Globe-COORD Coordinate {{ point [
          {", ".join(vec(*p) for p in points)} ] }}
        normal Normal {{ vector [
          {", ".join(vec(*n) for n in normals)} ] }}
        normalPerVertex TRUE
        texCoord DEF Globe-TEXCOORD TextureCoordinate {{ point [
          {", ".join(vec(*t) for t in tex)} ] }}
        coordIndex [ {indices} ]
        normalIndex [ {indices} ]
        texCoordIndex [ {indices} ]
      }}
    }}
  ]
}}
""")


# A unit box (centred, 1 x 1 x 1) as six quads: the link every arm segment USEs.
BOX_POINTS = [(x, y, z) for z in (-0.5, 0.5) for y in (-0.5, 0.5) for x in (-0.5, 0.5)]
BOX_FACES = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]


def box_faces():
    indices = " ".join(" ".join(str(k) for k in f) + " -1," for f in BOX_FACES)
    return f"""DEF Link-FACES IndexedFaceSet {{
              ccw TRUE
              solid TRUE
              coord DEF Link-COORD Coordinate {{ point [ {", ".join(vec(*p) for p in BOX_POINTS)} ] }}
              coordIndex [ {indices} ]
            }}"""


def arm(out):
    """A robot arm: each joint a Transform turned about its pivot, holding its link and the
    next joint, twelve levels deep; links share one face set and two materials."""
    joints = [("Base", 0.35, 0.0), ("Shoulder", 0.3, 0.5), ("UpperArm", 0.9, -0.4),
              ("Elbow", 0.25, 0.9), ("Forearm", 0.8, 0.3), ("Wrist", 0.2, -0.6),
              ("Hand", 0.25, 0.2), ("Palm", 0.15, 0.1), ("Knuckle", 0.12, 0.3),
              ("Finger", 0.3, 0.2), ("Tip", 0.15, 0.3), ("Nail", 0.06, 0.1)]
    indent = "  "
    text = ["DEF Arm Transform {\n  translation 4.2 0 -0.5\n  children [\n"]
    closing = []
    for depth, (name, length, angle) in enumerate(joints):
        pad = indent * (2 + 2 * depth)
        width = 0.5 * 0.8**depth
        material = "Steel-MAT" if depth % 2 == 0 else "Rubber-MAT"
        if depth == 0:
            appearance = (
                "appearance Appearance { material DEF Steel-MAT Material {"
                " diffuseColor 0.55 0.57 0.6 specularColor 0.8 0.8 0.8 shininess 0.6 } }"
            )
        elif depth == 1:
            appearance = (
                "appearance Appearance { material DEF Rubber-MAT Material {"
                " diffuseColor 0.9 0.45 0.1 ambientIntensity 0.25 } }"
            )
        else:
            appearance = f"appearance Appearance {{ material USE {material} }}"
        geometry = box_faces() if depth == 0 else "USE Link-FACES"
        text.append(f"""{pad}DEF {name} Transform {{
{pad}  translation 0 {num(0 if depth == 0 else joints[depth - 1][1])} 0
{pad}  rotation 0 0 1 {num(angle)}
{pad}  center 0 0 0
{pad}  children [
{pad}    DEF {name}-LINK Transform {{
{pad}      translation 0 {num(length / 2)} 0
{pad}      scale {vec(width, length, width)}
{pad}      children Shape {{
{pad}        {appearance}
{pad}        geometry {geometry}
{pad}      }}
{pad}    }}
""")
        closing.append(f"{pad}  ]\n{pad}}}\n")
    text.extend(reversed(closing))
    text.append("  ]\n}\n")
    out.append("".join(text))
    out.append("""DEF Arm-TIMER TimeSensor { loop TRUE cycleInterval 4 }
DEF Elbow-ROT-INTERP OrientationInterpolator {
  key [ 0, 0.5, 1 ]
  keyValue [ 0 0 1 0.9, 0 0 1 0.3, 0 0 1 0.9 ]
}
ROUTE Arm-TIMER.fraction_changed TO Elbow-ROT-INTERP.set_fraction
ROUTE Elbow-ROT-INTERP.value_changed TO Elbow.set_rotation
""")


def posts(out):
    """A row of fence posts: the first DEF'd, the others USE it, as exporters write instances."""
    out.append("""DEF Post01 Transform {
  translation -6 0.6 -2.5
  children Shape {
    appearance Appearance { material DEF Wood-MAT Material { diffuseColor 0.55 0.35 0.2 } }
    geometry Cylinder { radius 0.12 height 1.2 }
  }
}
""")
    for k in range(2, 9):
        out.append(f"Transform {{ translation {num((k - 1) * 1.1)} 0 0 children USE Post01 }}\n")


def ground(out):
    out.append("""DEF Ground Transform {
  children Shape {
    appearance Appearance { material Material { diffuseColor 0.45 0.5 0.4 ambientIntensity 0.4 } }
    geometry IndexedFaceSet {
      coord Coordinate { point [ -8 0 -6, 8 0 -6, 8 0 6, -8 0 6 ] }
      coordIndex [ 0 3 2 1 -1 ]
    }
  }
}
""")


def world():
    out = ["""#VRML V2.0 utf8

# Produced by scripts/make_exported_vrml.py in the style of a modelling tool's VRML97
# exporter: DEF'd Transforms nested as deep as the model, large face sets with their own
# normals and texture coordinates, shared materials and meshes, animation routes.

WorldInfo { title "Exported workshop" info [ "Tessera sample: an exporter-style world" ] }
NavigationInfo { headlight FALSE type [ "EXAMINE", "ANY" ] }
Background {
  skyColor [ 0.25 0.4 0.75, 0.55 0.65 0.8, 0.85 0.85 0.8 ]
  skyAngle [ 1.1, 1.5708 ]
  groundColor [ 0.2 0.18 0.15, 0.35 0.33 0.3 ]
  groundAngle [ 1.5708 ]
}
DEF Camera01 Viewpoint {
  position 0 3.2 11
  orientation -1 0 0 0.18
  fieldOfView 0.7
  description "Camera01"
}
DEF Sun DirectionalLight { direction -0.4 -0.8 -0.45 intensity 0.9 ambientIntensity 0.35 }
DEF Fill PointLight { location -5 4 6 intensity 0.35 attenuation 1 0 0 radius 40 }
"""]
    ground(out)
    globe(out)
    arm(out)
    posts(out)
    return "".join(out)


def main():
    path = sys.argv[1] if len(sys.argv) > 1 else "scenes/vrml/exported.wrl.gz"
    with gzip.GzipFile(path, "wb", mtime=0) as f:  # mtime 0: the same bytes every time
        f.write(world().encode())


if __name__ == "__main__":
    main()
