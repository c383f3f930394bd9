"""The distortion picture: the UV layout, faces coloured by log area ratio, as a Blender image.

As `icm_param --png` draws it: blue where a face shrank, red where it grew (full colour at a
ratio of e or 1/e), white where it kept its area, against the others at the one texel density
of the atlas; the edges of the original faces (not the diagonals of the n-gons cut into
triangles) drawn dark. Drawn with numpy, one triangle at a time, so that it runs headless too.
"""

import numpy as np

BACKGROUND = (0.25, 0.25, 0.25)
EDGE = (0.05, 0.05, 0.05)


def log_area_ratios(V, F, uv, fuv):
    """log((UV area / total UV area) / (3D area / total 3D area)) of every triangle."""
    a, b, c = V[F[:, 0]], V[F[:, 1]], V[F[:, 2]]
    area3 = 0.5 * np.linalg.norm(np.cross(b - a, c - a), axis=1)
    p, q, r = uv[fuv[:, 0]], uv[fuv[:, 1]], uv[fuv[:, 2]]
    e1, e2 = q - p, r - p
    area2 = 0.5 * np.abs(e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0])
    ratio = (area2 / max(area2.sum(), 1e-300)) / (area3 / max(area3.sum(), 1e-300))
    return np.log(np.maximum(ratio, 1e-12))


def colours(log_ratios):
    """RGB (m, 3): white at 0, towards blue below and red above, saturated at +-1."""
    t = np.clip(log_ratios, -1.0, 1.0)[:, None]
    white = np.ones(3)
    blue = np.array([0.15, 0.3, 0.9])
    red = np.array([0.9, 0.15, 0.1])
    return np.where(t < 0, white + (-t) * (blue - white), white + t * (red - white))


def draw_triangle(image, p, colour, edges):
    """Fills the triangle p (3, 2, in pixels) and darkens its edges flagged in `edges`."""
    size = image.shape[0]
    lo = np.clip(np.floor(p.min(axis=0)).astype(int), 0, size)
    hi = np.clip(np.ceil(p.max(axis=0)).astype(int) + 1, 0, size)
    if np.any(hi <= lo):
        return
    X, Y = np.meshgrid(np.arange(lo[0], hi[0]) + 0.5, np.arange(lo[1], hi[1]) + 0.5)
    doubled = (p[1, 0] - p[0, 0]) * (p[2, 1] - p[0, 1]) - (p[1, 1] - p[0, 1]) * (p[2, 0] - p[0, 0])
    if doubled == 0.0:
        return
    sign = 1.0 if doubled > 0 else -1.0
    inside = np.ones(X.shape, dtype=bool)
    on_edge = np.zeros(X.shape, dtype=bool)
    for i in range(3):
        s, t = p[i], p[(i + 1) % 3]
        length = max(float(np.hypot(*(t - s))), 1e-12)
        distance = sign * ((t[0] - s[0]) * (Y - s[1]) - (t[1] - s[1]) * (X - s[0])) / length
        inside &= distance >= -0.5
        if edges[i]:
            on_edge |= distance < 0.5
    block = image[lo[1] : hi[1], lo[0] : hi[0]]
    block[inside] = colour
    block[inside & on_edge] = EDGE


def rasterize(uv, fuv, face_colours, original_edges, size):
    """An RGB float image (size, size, 3), row 0 at v = 0 (Blender's order of pixels)."""
    image = np.empty((size, size, 3))
    image[:] = BACKGROUND
    corners = uv[fuv] * size
    for t in range(len(fuv)):
        draw_triangle(image, corners[t], face_colours[t], original_edges[t])
    return image


def original_edges(corner_loops):
    """(m, 3) bools: whether the side from corner i to i + 1 is an edge of the original face."""
    flags = np.zeros((len(corner_loops), 3), dtype=bool)
    for t, tri in enumerate(corner_loops):
        for i in range(3):
            a, b = tri[i], tri[(i + 1) % 3]
            flags[t, i] = a.link_loop_next == b or b.link_loop_next == a
    return flags


def make_image(bpy, name, rgb, path):
    """The Blender image `name` (replaced if it exists) holding rgb; saved as PNG at path if given."""
    size = rgb.shape[0]
    old = bpy.data.images.get(name)
    if old is not None:
        bpy.data.images.remove(old)
    image = bpy.data.images.new(name, size, size, alpha=False)
    rgba = np.ones((size, size, 4), dtype=np.float32)
    rgba[:, :, :3] = rgb
    image.pixels.foreach_set(rgba.ravel())
    if path:
        image.filepath_raw = path
        image.file_format = "PNG"
        image.save()
    return image


def distortion_picture(bpy, arrays, uv, fuv, size, path, name="ICM distortion"):
    """Draws the layout of an unwrap into the image `name`; returns the image."""
    ratios = log_area_ratios(arrays.V, arrays.F, uv, fuv)
    rgb = rasterize(uv, fuv, colours(ratios), original_edges(arrays.corner_loops), size)
    return make_image(bpy, name, rgb, path)
