"""The worked math beside a picked ray or vertex, typeset as the lecture writes it.

:class:`WorkedMath` shows, for the first hit of a picked pixel's ray,

- a sphere: the ray's parametric form, ``a``, ``b``, ``c``, ``Δ``, both roots,
  the root taken and why, the hit point (:mod:`core.image_order.intersect_sphere`);
- a triangle: the system ``o + t d = αA + βB + (1 − α − β)C``, its solution by
  Cramer's rule and the barycentric test (:mod:`core.image_order.intersect_triangle`);
- a reflection: the mirrored direction; a refraction: the angles, Snell's law
  and the Fresnel weights (:mod:`core.image_order.optics`);

and for a picked vertex its path through the object-order stages, world,
camera, clip, NDC and pixel, with the matrix of each map
(:func:`core.projection.project_point`), and the point and its image in the lecture's
coordinates, the screen at z = 0 (:func:`core.projection.lecture_screen_point`), the form
the perspective and orthographic lessons work.  Every number comes from those core
functions, the ones ``python -m app intersect`` prints, at the same 6
significant digits.  The formulas are typeset off the GUI thread (``MathView``'s
``later``) and show once typeset; :meth:`WorkedMath.typesetting` says whether
any is still on its way.
"""

from __future__ import annotations

import math

import numpy as np
from PySide6.QtCore import Qt
from PySide6.QtGui import QFont
from PySide6.QtWidgets import QGridLayout, QLabel, QScrollArea, QVBoxLayout, QWidget

from core.camera import Camera
from core.image_order import optics
from core.image_order.intersect_sphere import SphereIntersection, intersect_sphere
from core.image_order.intersect_triangle import TriangleIntersection, cramer_solve
from core.image_order.mesh_hit import first_triangle_hit
from core.image_order.ray_tree import RayNode
from core.projection import ProjectedPoint, lecture_screen_point, project_point
from core.scene import Scene, Sphere
from core.shown_numbers import shown_number as _g
from views.text.math_view import MathView, MatrixView

PROMPT = "Pick a pixel in the image-order pane to see how its first hit is found."


def _v(v) -> str:
    return "(" + ",\\ ".join(_g(float(x)) for x in v) + ")"


def _signed(x: float) -> str:
    return f"- {_g(-x)}" if x < 0 else f"+ {_g(x)}"


def _unit(v) -> np.ndarray:
    v = np.asarray(v, dtype=float)
    return v / np.linalg.norm(v)


class WorkedMath(QScrollArea):
    """A scrolling list of headed sections, each a column of labelled typeset formulas.

    Use :meth:`show_ray` for a picked pixel, :meth:`show_vertex` for a picked
    vertex, or the ``show_*`` methods for one crossing; :meth:`rows` gives what
    is shown as text.
    """

    def __init__(self, parent: QWidget | None = None):
        super().__init__(parent)
        self.setWidgetResizable(True)
        self._scale = 1.0
        self._rows: list[tuple[str, str]] = []
        self._body = QWidget()
        self._layout = QVBoxLayout(self._body)
        self._layout.setAlignment(Qt.AlignmentFlag.AlignTop)
        self.setWidget(self._body)
        self.clear()

    # --- what is shown ------------------------------------------------------

    def rows(self) -> list[tuple[str, str]]:
        """Every row shown, ``(label, formula or text)``, top to bottom (headings have label "")."""
        return list(self._rows)

    def value(self, label: str) -> str:
        """The formula or text of the first row labelled ``label``."""
        for name, text in self._rows:
            if name == label:
                return text
        raise KeyError(label)

    def typesetting(self) -> bool:
        """Whether a formula shown is still being typeset (off the GUI thread)."""
        return any(view.pending for view in self._body.findChildren(MathView))

    def set_scale(self, scale: float) -> None:
        """Enlarge every formula and label by ``scale`` (presentation mode)."""
        self._scale = float(scale)
        for w in self._body.findChildren(QWidget):
            if isinstance(w, (MathView, MatrixView)):
                w.set_scale(scale)

    def clear(self, message: str = PROMPT) -> None:
        """Show only ``message``."""
        self._start()
        note = QLabel(message)
        note.setWordWrap(True)
        self._layout.addWidget(note)
        self._rows.append(("", message))

    def _start(self) -> None:
        while self._layout.count():
            item = self._layout.takeAt(0)
            if item.widget() is not None:
                item.widget().hide()
                item.widget().deleteLater()
        self._rows = []
        self._grid = None
        self._vertex = None  # (point, camera, name) while a vertex's path is shown

    def _heading(self, text: str) -> None:
        label = QLabel(text)
        font = QFont()  # only the weight: the size follows the window (presentation scale)
        font.setBold(True)
        label.setFont(font)
        label.setWordWrap(True)
        self._layout.addWidget(label)
        self._rows.append(("", text))
        body = QWidget()
        self._grid = QGridLayout(body)
        self._grid.setContentsMargins(8, 0, 0, 6)
        self._grid.setColumnStretch(1, 1)
        self._layout.addWidget(body)

    def _row(self, label: str, formula: str = "", text: str = "", matrix=None) -> None:
        r = self._grid.rowCount()
        name = QLabel(label)
        name.setAlignment(Qt.AlignmentFlag.AlignRight | Qt.AlignmentFlag.AlignVCenter)
        self._grid.addWidget(name, r, 0)
        if formula:
            view = MathView(formula, self._grid.parentWidget(), scale=self._scale, later=True)
            self._grid.addWidget(view, r, 1)
        elif matrix is not None:
            view = MatrixView(matrix)
            view.set_scale(self._scale)
            self._grid.addWidget(view, r, 1, Qt.AlignmentFlag.AlignLeft)
        else:
            view = QLabel(text)
            view.setWordWrap(True)
            self._grid.addWidget(view, r, 1)
        self._rows.append((label, formula or text or str(np.asarray(matrix).tolist())))

    # --- image order --------------------------------------------------------

    def show_ray(self, scene: Scene, root: RayNode) -> None:
        """The first hit of a pixel's primary ray ``root``, then its reflection and refraction, if any.

        ``root`` is what :func:`core.image_order.ray_tree.trace_pixel` returns for ``scene``.
        """
        self._start()
        if root.hit is None:
            self._heading("The ray hits nothing")
            self._row("ray", rf"$\mathbf{{r}}(t) = {_v(root.origin)} + t\,{_v(root.direction)}$")
            self._row("", text="No object lies on it, so the pixel gets the background colour.")
            return
        obj = scene.objects[root.hit]
        if isinstance(obj, Sphere):
            self._sphere(intersect_sphere(root.origin, root.direction, obj.center, obj.radius), obj.name)
        else:
            found = first_triangle_hit(obj, root.origin, root.direction)
            if found is None:  # the kernel's hit was within rounding of an edge the exact test rejects
                self._heading(f"First hit: {obj.name}")
                self._row("", text="The exact triangle test finds no crossing here (a grazing ray).")
            else:
                self._triangle(found[1], f"{obj.name}, triangle {found[0]}")
        d, n = _unit(root.direction), np.asarray(root.normal, dtype=float)
        for child in root.children:
            if child.kind == "reflection":
                self.show_reflection(d, n)
            elif child.kind == "refraction":
                ior = obj.material.ior
                n1, n2 = (1.0, ior) if root.front_face else (ior, 1.0)
                self.show_refraction(d, n, n1, n2, keep=True)

    def show_sphere(self, s: SphereIntersection, name: str = "sphere") -> None:
        """The worked crossing ``s`` of a ray or segment with a sphere."""
        self._start()
        self._sphere(s, name)

    def _sphere(self, s: SphereIntersection, name: str) -> None:
        o, d, c, r = s.origin, s.direction, s.center, s.radius
        self._heading(f"Crossing the ray with the sphere: {name}")
        self._row("sphere", rf"$(x {_signed(-c[0])})^2 + (y {_signed(-c[1])})^2 + (z {_signed(-c[2])})^2"
                            rf" = {_g(r)}^2$")
        limits = r"0 \leq t \leq 1" if s.is_segment else r"t \geq 0"
        for k, axis in enumerate("xyz"):
            self._row("ray" if k == 0 else "", rf"${axis} = {_g(o[k])} {_signed(d[k])}t$")
        self._row("", rf"${limits}$")
        self._row("a", rf"$a = i^2 + j^2 + k^2 = {_g(s.a)}$")
        self._row("b", rf"$b = 2[i(x_1-l) + j(y_1-m) + k(z_1-n)] = {_g(s.b)}$")
        self._row("c", rf"$c = (x_1-l)^2 + (y_1-m)^2 + (z_1-n)^2 - r^2 = {_g(s.c)}$")
        self._row("Δ", rf"$\Delta = b^2 - 4ac = {_g(s.discriminant)}$")
        verdict = {"misses": "Δ < 0: the line misses the sphere",
                   "tangent": "Δ = 0: the line touches the sphere",
                   "crosses": "Δ > 0: the line crosses the sphere twice"}[s.classification]
        self._row("", text=verdict)
        if s.t_near is not None:
            self._row("t_near", rf"$t_1 = \dfrac{{-b - \sqrt{{\Delta}}}}{{2a}} = {_g(s.t_near)}$")
            self._row("t_far", rf"$t_2 = \dfrac{{-b + \sqrt{{\Delta}}}}{{2a}} = {_g(s.t_far)}$")
        self._row("choice", text=s.reason + ".")
        if s.hit:
            self._row("t", rf"$t = {_g(s.t)}$")
            self._row("hit point", rf"$P = \mathbf{{o}} + t\,\mathbf{{d}} = {_v(s.point)}$")
        if s.is_segment and s.ray_hit_t is not None and not s.hit:
            p = o + s.ray_hit_t * d
            self._row("ray beyond", rf"$t = {_g(s.ray_hit_t)}:\ \ P = {_v(p)}$")

    def show_triangle(self, h: TriangleIntersection, name: str = "triangle") -> None:
        """The worked crossing ``h`` of a ray with a triangle."""
        self._start()
        self._triangle(h, name)

    def _triangle(self, h: TriangleIntersection, name: str) -> None:
        A, B, C = h.vertices
        s = cramer_solve(h.origin, h.direction, A, B, C)
        self._heading(f"Crossing the ray with the triangle: {name}")
        self._row("system", r"$\mathbf{o} + t\,\mathbf{d} = \alpha\mathbf{A} + \beta\mathbf{B} + "
                            r"(1-\alpha-\beta)\mathbf{C}$")
        self._row("ray", rf"$\mathbf{{o}} = {_v(h.origin)},\ \ \mathbf{{d}} = {_v(h.direction)}$")
        self._row("corners", rf"$\mathbf{{A}} = {_v(A)},\ \mathbf{{B}} = {_v(B)},\ \mathbf{{C}} = {_v(C)}$")
        self._row("as matrix", r"$[\,\mathbf{A}-\mathbf{C}\ \ \mathbf{B}-\mathbf{C}\ \ -\mathbf{d}\,]"
                               r"\,(\alpha, \beta, t)^T = \mathbf{o} - \mathbf{C}$")
        self._row("M | o − C", matrix=np.column_stack([s.matrix, s.rhs]))
        self._row("det M", rf"$\det M = {_g(s.det)}$")
        if s.det == 0:
            self._row("", text="det M = 0: the ray runs parallel to the triangle's plane.")
            return
        self._row("α", rf"$\alpha = \det M_\alpha / \det M = {_g(s.alpha)}$")
        self._row("β", rf"$\beta = \det M_\beta / \det M = {_g(s.beta)}$")
        self._row("γ", rf"$\gamma = 1 - \alpha - \beta = {_g(s.gamma)}$")
        self._row("t", rf"$t = \det M_t / \det M = {_g(s.t)}$")
        geq = r"\geq"
        signs = r",\ ".join(f"{n} {geq if v >= 0 else '<'} 0"
                             for n, v in zip((r"\alpha", r"\beta", r"\gamma", "t"),
                                             (s.alpha, s.beta, s.gamma, s.t), strict=True))
        self._row("test", f"${signs}$")
        if h.hit:
            self._row("hit point", rf"$P = \alpha\mathbf{{A}} + \beta\mathbf{{B}} + \gamma\mathbf{{C}} = "
                                   rf"{_v(h.point)}$")
        else:
            self._row("", text=f"No hit: {h.reason}.")

    def show_reflection(self, d, n) -> None:
        """The mirror direction of unit ``d`` at unit normal ``n`` (facing the ray)."""
        r = optics.reflect(tuple(d), tuple(n))
        cos_i = -optics.dot(d, n)
        self._heading("Reflection")
        self._row("rule", r"$\mathbf{r} = \mathbf{d} - 2(\mathbf{d}\cdot\mathbf{n})\,\mathbf{n}$")
        self._row("d", rf"$\mathbf{{d}} = {_v(d)}$")
        self._row("n", rf"$\mathbf{{n}} = {_v(n)}$")
        self._row("r", rf"$\mathbf{{r}} = {_v(r)}$")
        angle = math.degrees(math.acos(max(-1.0, min(1.0, cos_i))))
        self._row("angles", rf"$\theta_{{in}} = \theta_{{out}} = {_g(angle)}^\circ$")

    def show_refraction(self, d, n, n1: float, n2: float, keep: bool = False) -> None:
        """Snell's law and the Fresnel weights for unit ``d`` at unit normal ``n`` (facing the ray)."""
        if not keep:
            self._start()
        cos_i = -optics.dot(d, n)
        theta1 = math.degrees(math.acos(max(-1.0, min(1.0, cos_i))))
        ok, t_dir = optics.refract(tuple(d), tuple(n), n1 / n2)
        reflectance, transmittance = optics.fresnel_dielectric(cos_i, n1, n2)
        self._heading("Refraction")
        self._row("Snell", rf"$n_1 \sin\theta_1 = n_2 \sin\theta_2,\ \ n_1 = {_g(n1)},\ n_2 = {_g(n2)}$")
        self._row("θ1", rf"$\theta_1 = {_g(theta1)}^\circ$")
        if ok:
            theta2 = math.degrees(math.asin(min(1.0, n1 / n2 * math.sin(math.radians(theta1)))))
            self._row("θ2", rf"$\theta_2 = \arcsin(\dfrac{{n_1}}{{n_2}}\sin\theta_1) = {_g(theta2)}^\circ$")
            self._row("t", rf"$\mathbf{{t}} = {_v(t_dir)}$")
        else:
            critical = optics.critical_angle_deg(n1, n2)
            self._row("", text=f"Past the critical angle ({_g(critical)}°): total internal reflection.")
        self._row("Fresnel", rf"$R = {_g(reflectance)},\ \ T = {_g(transmittance)},\ \ R + T = 1$")

    # --- object order -------------------------------------------------------

    def _lecture_rows(self, view_point, camera: Camera) -> None:
        """The point ``A`` as the lecture writes it, the screen (the near plane) at z = 0, z into the
        scene and, for perspective, the eye at z = -d (Fig. VII.6; Fig. VII.7 for parallel rays), and
        its image ``A'``: the formula the perspective and orthographic lessons work, with this point's
        numbers.  The row's label names the figure."""
        a, image = lecture_screen_point(view_point, camera.near, camera.projection)
        if camera.projection == "orthographic":
            self._row("Fig. VII.7", rf"$A = {_v(a)}$")
            self._row("A′", rf"$A' = (x,\ y) = {_v(image)}$")
            return
        self._row("Fig. VII.6", rf"$A = {_v(a)},\ \ d = n = {_g(camera.near)}$")
        if image is None:
            self._row("A′", text="z + d ≤ 0: the point is at or behind the eye and has no image.")
            return
        formula = r"A' = \left(\dfrac{x\,d}{z + d},\ \dfrac{y\,d}{z + d}\right)"
        self._row("A′", rf"${formula} = {_v(image)}$")

    def follow_camera(self, camera: Camera) -> None:
        """Work a shown vertex's path again for ``camera`` (the observer moved, or a lesson changed
        the projection), so the matrices shown are always the ones in use."""
        if self._vertex is not None and self._vertex[1] != camera:
            point, _, name = self._vertex
            self.show_vertex(point, camera, name)

    def show_vertex(self, point, camera: Camera, name: str = "vertex") -> ProjectedPoint:
        """The path of world point ``point`` through view, clip, NDC and pixel, with each map's matrix."""
        self._start()
        self._vertex = (point, camera, name)
        view_from_world, clip_from_view = camera.view_from_world, camera.clip_from_view
        p = project_point(point, view_from_world, clip_from_view, camera.width, camera.height)
        self._heading(f"The path of {name} through the stages")
        self._row("world", rf"$\mathbf{{p}}_{{world}} = {_v(p.world)}$")
        self._row("view ← world", matrix=view_from_world)
        self._row("camera", rf"$\mathbf{{p}}_{{view}} = {_v(p.view)},\ \ \mathrm{{depth}} = {_g(p.depth)}$")
        self._lecture_rows(p.view, camera)
        self._row("clip ← view", matrix=clip_from_view)
        self._row("clip", rf"$(x_c, y_c, z_c, w) = {_v(p.clip)}$")
        if p.ndc is None:
            self._row("", text="w ≤ 0: the point is behind the eye; clipping removes it before the divide.")
            return p
        self._row("NDC", rf"$(x_c, y_c, z_c) / w = {_v(p.ndc)}$")
        self._row("pixel", rf"$x = \dfrac{{x_n + 1}}{{2}}\,{camera.width} = {_g(p.pixel[0])},\ \ "
                           rf"y = \dfrac{{1 - y_n}}{{2}}\,{camera.height} = {_g(p.pixel[1])}$")
        self._row("", text="Inside the frustum." if p.inside else "Outside the frustum: clipped.")
        return p
