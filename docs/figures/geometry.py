"""The geometry figures of docs/monte_carlo.md: the solid angle dω = sin θ dθ dφ, the change
of variables dω = cos θy dA / d², and Malley's method (uniform disk points lifted to the
hemisphere give the density cos θ / π). Not part of the article: its pictures; drawn by
make_figures.py with the chapter's notation."""
import numpy as np
import matplotlib.pyplot as plt
from matplotlib.patches import Arc, Polygon
from mpl_toolkits.mplot3d import Axes3D  # noqa: F401  (registers the 3d projection)

BLUE, ORANGE, GREY = "#1f77b4", "#d62728", "#888888"


def sph(theta, phi, r=1.0):
    theta, phi = np.broadcast_arrays(theta, phi)
    return np.array([r * np.sin(theta) * np.cos(phi), r * np.sin(theta) * np.sin(phi), r * np.cos(theta)])


def solid_angle():
    """A hemisphere, a direction ω at (θ, φ), and the patch dω it sweeps for dθ and dφ."""
    fig = plt.figure(figsize=(5.2, 4.4))
    ax = fig.add_subplot(projection="3d")
    ax.view_init(elev=22, azim=-20)
    for phi in np.linspace(0, 2 * np.pi, 13)[:-1]:  # meridians
        t = np.linspace(0, np.pi / 2, 30)
        ax.plot(*sph(t, phi), color=GREY, lw=0.4, alpha=0.6)
    for theta in np.linspace(np.pi / 12, np.pi / 2, 6):  # circles of latitude
        p = np.linspace(0, 2 * np.pi, 90)
        ax.plot(*sph(theta, p), color=GREY, lw=0.4, alpha=0.6)
    theta, phi, dt, dp = 0.8, 0.55, 0.25, 0.4
    # the patch swept by dθ, dφ
    t = np.linspace(theta, theta + dt, 8)
    p = np.linspace(phi, phi + dp, 8)
    edge = np.concatenate([sph(t, phi), sph(theta + dt, p), sph(t[::-1], phi + dp), sph(theta, p[::-1])], axis=1)
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection
    ax.add_collection3d(Poly3DCollection([edge.T], facecolor=ORANGE, alpha=0.55, edgecolor=ORANGE))
    # the normal, the direction, its projection on the surface
    ax.quiver(0, 0, 0, 0, 0, 1.25, color="k", lw=1.2, arrow_length_ratio=0.08)
    ax.text(0, 0, 1.3, "n", fontsize=11)
    w = sph(theta, phi)  # the patch's corner: θ and φ are drawn to it
    ax.quiver(0, 0, 0, *(1.0 * w), color=BLUE, lw=1.5, arrow_length_ratio=0.1)
    ax.text(*(1.1 * w), "ω", color=BLUE, fontsize=12, ha="right")
    base = np.array([np.cos(phi), np.sin(phi), 0.0])
    ax.plot([0, np.sin(theta) * base[0]], [0, np.sin(theta) * base[1]], [0, 0], color=BLUE, lw=0.8, ls="--")
    ax.plot(*np.stack([np.sin(theta) * base, sph(theta, phi)], axis=1), color=BLUE, lw=0.8, ls=":")
    # θ arc from the normal, φ arc from the x axis
    ta = np.linspace(0, theta, 20)
    ax.plot(*sph(ta, phi, 0.35), color="k", lw=0.9)
    ax.text(*sph(theta / 2, phi, 0.45), "θ", fontsize=11)
    pa = np.linspace(0, phi, 20)
    ax.plot(0.35 * np.cos(pa), 0.35 * np.sin(pa), 0 * pa, color="k", lw=0.9)
    ax.text(0.42 * np.cos(phi / 2), 0.42 * np.sin(phi / 2), 0.0, "φ", fontsize=11)
    ax.text(*sph(theta + dt / 2, phi - 0.12, 1.05), "dθ", fontsize=9, color=ORANGE, ha="right")
    ax.text(*sph(theta + dt + 0.06, phi + dp / 2, 1.06), "sin θ dφ", fontsize=9, color=ORANGE, va="top")
    ax.plot([-1, 1], [0, 0], [0, 0], color="k", lw=0.4)
    ax.plot([0, 0], [-1, 1], [0, 0], color="k", lw=0.4)
    ax.set_box_aspect((1, 1, 0.6), zoom=1.45)
    ax.set_xlim(-1, 1), ax.set_ylim(-1, 1), ax.set_zlim(0, 1.2)
    ax.set_axis_off()
    ax.set_title("dω = sin θ dθ dφ: the patch's area on the unit sphere")
    fig.subplots_adjust(left=0, right=1, bottom=0, top=0.95)
    return fig


def area_to_solid_angle():
    """A cut through x, the patch dA at y and the unit circle around x: dω = cos θy dA / d²."""
    fig, ax = plt.subplots(figsize=(6.4, 3.8))
    x = np.array([0.0, 0.0])
    y = np.array([3.4, 1.9])
    d = np.linalg.norm(y - x)
    wi = (y - x) / d
    tilt = np.deg2rad(-50)  # θy: the angle between n_y and −wi
    n_y = -np.array([np.cos(tilt) * wi[0] - np.sin(tilt) * wi[1], np.sin(tilt) * wi[0] + np.cos(tilt) * wi[1]])
    t = np.array([-n_y[1], n_y[0]])  # along the patch
    half = 0.55
    a, b = y - half * t, y + half * t
    ax.plot([-0.8, 1.2], [0, 0], color="k", lw=1.0)
    ax.add_patch(Polygon([[-0.8, 0], [1.2, 0], [1.2, -0.15], [-0.8, -0.15]], closed=True, color="#dddddd"))
    ax.annotate("", xy=(0, 0.7), xytext=(0, 0), arrowprops=dict(arrowstyle="->", lw=1.0))
    ax.text(0.05, 0.7, "n_x", fontsize=9)
    ax.plot(*x, "ko", ms=3)
    ax.text(-0.25, -0.35, "x", fontsize=11)
    ax.add_patch(Arc((0, 0), 2, 2, theta1=-5, theta2=185, color=GREY, lw=0.8, ls="--"))
    ax.text(-1.05, 0.35, "unit circle\naround x", fontsize=8, color=GREY, ha="right")
    for e in (a, b):  # the rays to the patch's ends
        ax.plot([0, e[0]], [0, e[1]], color=BLUE, lw=0.7)
    ang = np.degrees([np.arctan2(a[1], a[0]), np.arctan2(b[1], b[0])])
    ax.add_patch(Arc((0, 0), 2, 2, theta1=min(ang), theta2=max(ang), color=ORANGE, lw=3))
    mid = np.deg2rad(ang.mean())
    ax.text(1.1 * np.cos(mid) - 0.05, 1.1 * np.sin(mid) + 0.12, "dω", color=ORANGE, fontsize=12)
    ax.plot([a[0], b[0]], [a[1], b[1]], color=ORANGE, lw=3)
    top_end = a if a[1] > b[1] else b
    ax.text(*(top_end + np.array([0.12, -0.1])), "dA", color=ORANGE, fontsize=12)
    # the cross-section perpendicular to the line of sight: cos θy dA
    perp = np.array([-wi[1], wi[0]])
    c = half * np.cos(tilt)
    ax.plot(*np.stack([y - c * perp, y + c * perp], axis=1), color="k", lw=1.2, ls="--")
    low = y - c * perp if (y - c * perp)[1] < (y + c * perp)[1] else y + c * perp
    ax.text(*(low + np.array([0.1, -0.25])), "cos θy dA (dashed)", fontsize=9)
    ax.annotate("", xy=y + 0.8 * n_y, xytext=y, arrowprops=dict(arrowstyle="->", lw=1.0))
    ax.text(*(y + 0.85 * n_y + np.array([-0.1, 0.08])), "n_y", fontsize=9)
    ax.annotate("", xy=y - 0.8 * wi, xytext=y, arrowprops=dict(arrowstyle="->", lw=1.0, color=BLUE))
    ax.text(*(y - 0.9 * wi + np.array([-0.15, 0.1])), "−wi", fontsize=9, color=BLUE)
    ang_n = np.degrees(np.arctan2(n_y[1], n_y[0])) % 360
    ang_w = np.degrees(np.arctan2(-wi[1], -wi[0])) % 360
    ax.add_patch(Arc(y, 0.7, 0.7, theta1=min(ang_n, ang_w), theta2=max(ang_n, ang_w), lw=0.8))
    ax.text(*(y + 0.45 * (n_y - wi) / np.linalg.norm(n_y - wi) + np.array([-0.08, 0.0])), "θy", fontsize=10)
    ax.plot(*y, "ko", ms=3)
    ax.text(y[0] + 0.12, y[1] - 0.05, "y", fontsize=11)
    ax.annotate("", xy=y - 0.05 * wi, xytext=x + 1.05 * wi,
                arrowprops=dict(arrowstyle="<->", lw=0.6, color=GREY, shrinkA=0, shrinkB=0))
    mid_d = (x + y) / 2 + 0.3 * np.array([wi[1], -wi[0]]) - 0.2 * wi
    ax.text(*mid_d, "d = |y − x|", fontsize=9, color=GREY, rotation=np.degrees(np.arctan2(wi[1], wi[0])))
    ax.set_title("dω = cos θy · dA / d²   (tilted: cos θy; far: 1/d²)")
    ax.set_aspect("equal")
    ax.set_xlim(-1.9, 4.6), ax.set_ylim(-0.5, 3.0)
    ax.set_axis_off()
    fig.tight_layout()
    return fig


def malley(n=500, seed=1):
    """Uniform points on the unit disk, lifted to z = sqrt(1 − r²); their θ follows sin 2θ."""
    rng = np.random.default_rng(seed)
    u1, u2 = rng.random(n), rng.random(n)
    r, phi = np.sqrt(u1), 2 * np.pi * u2
    px, py = r * np.cos(phi), r * np.sin(phi)
    pz = np.sqrt(1 - r * r)
    fig, axs = plt.subplots(1, 3, figsize=(9.6, 3.2), gridspec_kw={"width_ratios": [1, 1.5, 1.2]})
    ax = axs[0]
    ax.add_patch(plt.Circle((0, 0), 1, fill=False, color="k", lw=0.8))
    ax.scatter(px, py, s=2, color=BLUE)
    ax.set_title("1. uniform on the disk:\nr = sqrt(u1), φ = 2π u2")
    ax.set_aspect("equal"), ax.set_xlim(-1.1, 1.1), ax.set_ylim(-1.1, 1.1), ax.set_axis_off()
    ax = axs[1]
    band = np.abs(py) < 0.08  # a thin slice y ≈ 0, seen from the side
    t = np.linspace(0, np.pi, 100)
    ax.plot(np.cos(t), np.sin(t), color="k", lw=0.8)
    ax.plot([-1.05, 1.05], [0, 0], color="k", lw=0.8)
    for xv, zv in zip(px[band], pz[band]):
        ax.plot([xv, xv], [0, zv], color=GREY, lw=0.4)
    ax.scatter(px[band], 0 * px[band], s=4, color=BLUE)
    ax.scatter(px[band], pz[band], s=6, color=ORANGE, zorder=3)
    ax.annotate("", xy=(0, 1.2), xytext=(0, 0), arrowprops=dict(arrowstyle="->", lw=1.0))
    ax.text(0.04, 1.15, "n", fontsize=10)
    ax.set_title("2. lifted to z = sqrt(1 − r²) = cos θ\n(the slice |y| < 0.08, from the side)")
    ax.set_aspect("equal"), ax.set_xlim(-1.1, 1.1), ax.set_ylim(-0.08, 1.3), ax.set_axis_off()
    ax = axs[2]
    theta = np.arccos(pz)
    ax.hist(theta, bins=18, range=(0, np.pi / 2), density=True, color=ORANGE, alpha=0.6,
            label=f"the {n} lifted points")
    tt = np.linspace(0, np.pi / 2, 100)
    ax.plot(tt, np.sin(2 * tt), color="k", lw=1.2, label="p_θ(θ) = sin 2θ")
    ax.set_xlabel("θ (radians)"), ax.set_ylabel("density of θ")
    ax.set_title("3. p_ω = cos θ / π,\nso p_θ(θ) = 2 cos θ sin θ")
    ax.legend(fontsize=7, loc="upper right")
    fig.tight_layout()
    return fig
