#!/usr/bin/env python3
"""Writes a Wavefront OBJ triangle mesh as a POV-Ray `mesh2`, unitized as Tessera unitizes OBJ
files on load (common/loaders/obj_loader.cpp): centred on its bounding box and scaled so that
the box's largest half-extent is 1. So the two renderers see the same triangles.

Faces must be triangles (`f a b c`, `f a//n ...` or `f a/t/n ...`); with normals on every
corner, the mesh2 gets them too and POV-Ray interpolates them as Tessera's `mesh <file> 1` does.

    bench/povray/obj_to_mesh2.py IN.obj NAME > OUT.inc     # declares NAME as the mesh2
"""

import sys


def main(path, name):
    positions, normals, faces = [], [], []
    with open(path) as f:
        for line in f:
            words = line.split()
            if not words:
                continue
            if words[0] == 'v':
                positions.append(tuple(float(w) for w in words[1:4]))
            elif words[0] == 'vn':
                normals.append(tuple(float(w) for w in words[1:4]))
            elif words[0] == 'f':
                if len(words) != 4:
                    sys.exit(f'{path}: only triangles are supported: {line.strip()}')
                corners = [w.split('/') for w in words[1:]]
                faces.append(([int(c[0]) - 1 for c in corners],
                              [int(c[2]) - 1 if len(c) > 2 and c[2] else None for c in corners]))
    lo = [min(p[i] for p in positions) for i in range(3)]
    hi = [max(p[i] for p in positions) for i in range(3)]
    centre = [lo[i] * 0.5 + hi[i] * 0.5 for i in range(3)]
    half = max(hi[i] * 0.5 - lo[i] * 0.5 for i in range(3))
    smooth = all(None not in n for _, n in faces)
    out = sys.stdout
    out.write(f'// {path}: {len(positions)} vertices, {len(faces)} triangles, unitized\n')
    out.write(f'#declare {name} = mesh2 {{\n  vertex_vectors {{ {len(positions)}\n')
    for p in positions:
        out.write('    <%.9g, %.9g, %.9g>,\n' % tuple((p[i] - centre[i]) / half for i in range(3)))
    out.write('  }\n')
    if smooth:
        out.write(f'  normal_vectors {{ {len(normals)}\n')
        for n in normals:
            out.write('    <%.9g, %.9g, %.9g>,\n' % n)
        out.write('  }\n')
    out.write(f'  face_indices {{ {len(faces)}\n')
    for v, _ in faces:
        out.write('    <%d, %d, %d>,\n' % tuple(v))
    out.write('  }\n')
    if smooth:
        out.write(f'  normal_indices {{ {len(faces)}\n')
        for _, n in faces:
            out.write('    <%d, %d, %d>,\n' % tuple(n))
        out.write('  }\n')
    out.write('}\n')


if __name__ == '__main__':
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
