# SPDX-License-Identifier: BSD-3-Clause
"""The design page's figures as Plotly figure dicts (plain JSON: no plotly.py objects, so a redraw
costs only the numbers), built from camfollower.design.views.

Every figure over the cam angle carries ``layout.meta.cursor_axes`` (its x axes), so the page's cursor
draws one vertical line per subplot; the profile carries the follower's positions for every angle in
``layout.meta.follower`` and draws it at the cursor.
"""

from __future__ import annotations

import math
from typing import Any, Dict, List, Optional, Sequence

import numpy as np

BLUE, ORANGE, GREY, RED, GREEN = "#1f77b4", "#ff7f0e", "#555555", "#d62728", "#2ca02c"
_FONT = {"family": "DejaVu Sans, Arial, sans-serif", "size": 12}


def _list(x) -> List[Optional[float]]:
    """A JSON array: NaN as null (a gap in the line)."""
    a = np.asarray(x, dtype=float)
    return [None if not math.isfinite(v) else float(v) for v in a.tolist()]


def _axis(title: str, **extra) -> Dict[str, Any]:
    return {"title": {"text": title}, "showgrid": True, "gridcolor": "#e5e5e5", "zeroline": False, **extra}


def _angle_axis(title: str = "") -> Dict[str, Any]:
    return _axis(title, range=[0, 360], tickvals=list(range(0, 361, 45)))


def _cursor_shapes(axes: Sequence[str], cursor_deg: float) -> List[Dict[str, Any]]:
    return [
        {
            "type": "line",
            "xref": ax,
            "yref": f"{ax.replace('x', 'y')} domain",
            "x0": cursor_deg,
            "x1": cursor_deg,
            "y0": 0,
            "y1": 1,
            "line": {"color": GREY, "width": 1, "dash": "dot"},
        }
        for ax in axes
    ]


def _stacked(rows: int, titles: Sequence[str], height: int, cursor_deg: float) -> Dict[str, Any]:
    """A layout of `rows` subplots sharing the cam-angle axis."""
    gap = 0.06
    h = (1.0 - gap * (rows - 1)) / rows
    layout: Dict[str, Any] = {
        "height": height,
        "margin": {"l": 75, "r": 20, "t": 30, "b": 95},
        "font": _FONT,
        "showlegend": True,
        "legend": {"orientation": "h", "y": -0.1, "yanchor": "top", "x": 0},
        "plot_bgcolor": "white",
        "hovermode": "x",
    }
    axes = []
    for i in range(rows):
        n = "" if i == 0 else str(i + 1)
        top = 1.0 - i * (h + gap)
        layout[f"yaxis{n}"] = _axis(titles[i], domain=[top - h, top], anchor=f"x{n}")
        layout[f"xaxis{n}"] = _angle_axis("cam angle θ (deg)" if i == rows - 1 else "")
        layout[f"xaxis{n}"].update(anchor=f"y{n}", matches="x" if i else None, showticklabels=i == rows - 1)
        if not i:
            layout["xaxis"].pop("matches")
        axes.append(f"x{n}")
    layout["shapes"] = _cursor_shapes(axes, cursor_deg)
    layout["meta"] = {"cursor_axes": axes}
    return layout


def _line(x, y, name: str, axis: int = 1, **style) -> Dict[str, Any]:
    n = "" if axis == 1 else str(axis)
    return {
        "type": "scatter",
        "mode": "lines",
        "x": _list(x),
        "y": _list(y),
        "name": name,
        "xaxis": f"x{n}",
        "yaxis": f"y{n}",
        "line": {"width": 1.4, **style},
    }


def svaj(k: Dict[str, Any], cursor_deg: float = 0.0) -> Dict[str, Any]:
    """Lift, velocity, acceleration and jerk of the rigid follower at the camshaft's speed."""
    u, r = k["lift_unit"], k["rate_unit"]
    titles = [f"lift ({u})", f"velocity ({r}/s)", f"acceleration ({r}/s²)", f"jerk ({r}/s³)"]
    layout = _stacked(4, titles, 560, cursor_deg)
    layout["showlegend"] = False
    layout["margin"]["b"] = 45
    layout["title"] = {"text": f"SVAJ at {k['rpm']:.6g} rpm (rigid follower)", "x": 0.01, "font": {"size": 14}}
    layout["margin"]["t"] = 40
    x = k["theta_deg"]
    data = [
        _line(x, k["lift"], "lift", 1, color=BLUE),
        _line(x, k["velocity"], "velocity", 2, color=BLUE),
        _line(x, k["acceleration"], "acceleration", 3, color=BLUE),
        _line(x, k["jerk"], "jerk", 4, color=BLUE),
    ]
    return {"data": data, "layout": layout}


def follower_at(k: Dict[str, Any], cursor_deg: float) -> Dict[str, Any]:
    """The follower at cam angle `cursor_deg` in the cam's frame: the roller (or the face's line) and
    the contact point (the same drawing the page's cursor script makes)."""
    p = k["profile"]
    i = int(round(cursor_deg / 360.0 * (len(p["surface_x"]) - 1)))
    sx, sy, rx, ry = p["surface_x"][i], p["surface_y"][i], p["reference_x"][i], p["reference_y"][i]
    r = p["roller_radius"]
    if r > 0:
        t = np.linspace(0.0, 2.0 * math.pi, 73)
        x, y = rx + r * np.cos(t), ry + r * np.sin(t)
    else:  # a face: its line through the contact point, along the surface's tangent
        j0, j1 = max(i - 1, 0), min(i + 1, len(p["surface_x"]) - 1)
        tx, ty = p["surface_x"][j1] - p["surface_x"][j0], p["surface_y"][j1] - p["surface_y"][j0]
        n = math.hypot(tx, ty) or 1.0
        half = 0.5 * k["base_radius_mm"]
        x = np.array([sx - half * tx / n, sx + half * tx / n])
        y = np.array([sy - half * ty / n, sy + half * ty / n])
    return {"x": _list(x), "y": _list(y), "contact": [float(sx), float(sy)]}


def profile(k: Dict[str, Any], cursor_deg: float = 0.0, colour_by: str = "pressure_angle") -> Dict[str, Any]:
    """The cam in its own frame, its surface coloured by |pressure angle| (deg), the pitch curve, and
    the follower at the cursor."""
    p = k["profile"]
    layout = {
        "height": 560,
        "margin": {"l": 60, "r": 20, "t": 40, "b": 90},
        "font": _FONT,
        "plot_bgcolor": "white",
        "title": {"text": "cam profile, coloured by |pressure angle|", "x": 0.01, "font": {"size": 14}},
        "xaxis": _axis("x (mm)", scaleanchor="y", scaleratio=1),
        "yaxis": _axis("y (mm)"),
        "legend": {"orientation": "h", "y": -0.12, "yanchor": "top"},
        "meta": {"cursor_axes": []},
    }
    if p is None:
        layout["title"]["text"] = "a barrel cam: no plate profile (see the developed groove: camfollower figures)"
        return {"data": [], "layout": layout}
    colour = np.abs(k["pressure_angle_deg"])
    hover = [f"θ = {t:.1f}°, |α| = {a:.1f}°" for t, a in zip(k["theta_deg"], colour)]
    f = follower_at(k, cursor_deg)
    data = [
        {
            "type": "scatter",
            "mode": "lines",
            "x": _list(p["reference_x"]),
            "y": _list(p["reference_y"]),
            "name": "pitch curve",
            "line": {"color": GREY, "width": 1, "dash": "dash"},
            "hoverinfo": "skip",
        },
        {
            "type": "scatter",
            "mode": "markers",
            "x": _list(p["surface_x"]),
            "y": _list(p["surface_y"]),
            "name": "cam surface",
            "text": hover,
            "hoverinfo": "text",
            "marker": {
                "size": 4,
                "color": _list(colour),
                "colorscale": "Viridis",
                "cmin": 0.0,
                "cmax": max(30.0, float(np.nanmax(colour)) if colour.size else 30.0),
                "colorbar": {"title": {"text": "|α| (deg)"}, "thickness": 12},
            },
        },
        {
            "type": "scatter",
            "mode": "lines",
            "x": f["x"],
            "y": f["y"],
            "name": "follower at cursor",
            "line": {"color": RED, "width": 2},
            "hoverinfo": "skip",
        },
        {
            "type": "scatter",
            "mode": "markers",
            "x": [f["contact"][0], 0.0],
            "y": [f["contact"][1], 0.0],
            "name": "contact point, cam centre",
            "marker": {"color": [RED, "black"], "size": [8, 9], "symbol": ["circle", "cross"]},
            "hoverinfo": "skip",
        },
    ]
    layout["meta"]["follower"] = {
        "reference_x": _list(p["reference_x"]),
        "reference_y": _list(p["reference_y"]),
        "surface_x": _list(p["surface_x"]),
        "surface_y": _list(p["surface_y"]),
        "roller_radius": p["roller_radius"],
        "face_half_length": 0.5 * k["base_radius_mm"],
    }
    return {"data": data, "layout": layout}


def geometry(k: Dict[str, Any], cursor_deg: float = 0.0, max_pressure_angle_deg: float = 30.0) -> Dict[str, Any]:
    """Pressure angle with its limit, and the surface radius of curvature with the roller's radius
    (a convex radius below it, or a face's below zero, cannot be cut)."""
    layout = _stacked(2, ["pressure angle (deg)", "radius (mm)"], 520, cursor_deg)
    layout["title"] = {"text": "pressure angle, surface radius of curvature", "x": 0.01, "font": {"size": 14}}
    layout["margin"]["t"] = 40
    if "pressure_angle_deg" not in k:
        return {"data": [], "layout": layout}
    x = k["theta_deg"]
    rho = np.asarray(k["surface_radius_mm"], dtype=float)
    limit = 10.0 * k["base_radius_mm"] if k["base_radius_mm"] > 0 else np.inf
    rho = np.where(np.abs(rho) <= limit, rho, np.nan)  # near-straight flanks: a gap, not a plateau
    data = [
        _line(x, k["pressure_angle_deg"], "pressure angle", 1, color=BLUE),
        _line([0, 360], [max_pressure_angle_deg] * 2, f"limit ±{max_pressure_angle_deg:g}°", 1, color=RED, dash="dash"),
        _line([0, 360], [-max_pressure_angle_deg] * 2, "", 1, color=RED, dash="dash"),
        _line(x, rho, "surface radius (gap beyond ±10 r_b)", 2, color=BLUE),
        _line([0, 360], [0, 0], "0: cusp / undercut", 2, color=RED, dash="dash"),
    ]
    data[2]["showlegend"] = False
    return {"data": data, "layout": layout}


def response(r: Dict[str, Any], rpm: float, cursor_deg: float = 0.0, label: str = "") -> Dict[str, Any]:
    """The flexible response at the camshaft's speed: the follower's acceleration against the rigid
    one, the contact force with contact loss shaded, and the residual vibration in the dwells."""
    u = r["unit"]
    titles = [f"acceleration ({u}/s²)", "contact force (N)", f"residual ({'µm' if u == 'm' else 'µrad'})"]
    layout = _stacked(3, titles, 560, cursor_deg)
    s = r["summary"]
    layout["title"] = {
        "text": f"flexible response at {rpm:.6g} rpm (periodic steady state{label})",
        "x": 0.01,
        "font": {"size": 14},
    }
    layout["margin"]["t"] = 90
    x = np.asarray(r["theta_deg"])
    lost = np.asarray(r["lost"], dtype=bool)
    data = [
        _line(x, r["acceleration"], f"a.{r['dof']} (flexible)", 1, color=BLUE),
        _line(x, r["rigid_acceleration"], "rigid ω²h″", 1, color="black", dash="dash", width=1),
        _line(x, r["force"], "contact force", 2, color=BLUE),
        _line(x, 1e6 * np.asarray(r["residual"], dtype=float), "residual vibration (dwells)", 3, color=GREEN),
    ]
    shapes = layout["shapes"]
    # Contact loss: shaded spans on the force plot.
    edges = np.flatnonzero(np.diff(np.concatenate(([0], lost.astype(int), [0]))))
    for a, b in zip(edges[::2], edges[1::2]):
        shapes.append(
            {
                "type": "rect",
                "xref": "x2",
                "yref": "y2 domain",
                "x0": float(x[a]),
                "x1": float(x[min(b, len(x) - 1)]),
                "y0": 0,
                "y1": 1,
                "fillcolor": RED,
                "opacity": 0.2,
                "line": {"width": 0},
            }
        )
    if lost.any():
        data.append(_line([None], [None], "contact lost", 2, color=RED, width=8))
        data[-1]["opacity"] = 0.3
    layout["annotations"] = [
        {
            "text": (
                f"min force {s['min_force_N']:.4g} N at {s['min_force_angle_deg']:.1f}°"
                + (f", contact lost first at {s['first_loss_angle_deg']:.1f}°" if s["contact_lost"] else "")
                + f"; dwell residual {1e6 * s['dwell_residual']:.3g} {'µm' if u == 'm' else 'µrad'} p-p<br>"
                + f"accuracy {s['accuracy']:.1e} of the peak force and acceleration "
                + f"({s['steps_per_revolution']} steps per revolution)"
            ),
            "xref": "paper",
            "yref": "paper",
            "x": 0,
            "y": 1.13,
            "showarrow": False,
            "xanchor": "left",
            "font": {"size": 11, "color": GREY},
        }
    ]
    return {"data": data, "layout": layout}


def margin(
    rows: Sequence[Dict[str, Any]], speeds: Sequence[float], jump: Optional[Dict[str, Any]] = None
) -> Dict[str, Any]:
    """Minimum contact force of the steady state against camshaft speed (computed so far), contact loss
    marked, and the first contact loss found by the jump-speed search."""
    done = [r for r in rows if "min_force_N" in r]
    ok = [r for r in done if not r.get("contact_lost")]
    bad = [r for r in done if r.get("contact_lost")]
    lo, hi = (min(speeds), max(speeds)) if speeds else (0, 1)
    title = f"margin curve: {len(done)} of {len(speeds)} speeds"
    if jump and jump.get("rpm") is not None:
        title += f"; first contact loss at {jump['rpm']:.5g} rpm"
    elif jump and jump.get("message"):
        title += f"; {jump['message']}"
    data = [
        {
            "type": "scatter",
            "mode": "lines+markers",
            "x": [r["rpm"] for r in done],
            "y": [r["min_force_N"] for r in done],
            "name": "min contact force",
            "line": {"color": BLUE, "width": 1.4},
        },
        {
            "type": "scatter",
            "mode": "markers",
            "x": [r["rpm"] for r in bad],
            "y": [r["min_force_N"] for r in bad],
            "name": "contact lost",
            "marker": {"color": RED, "size": 10, "symbol": "x"},
        },
    ]
    shapes = [
        {"type": "line", "xref": "paper", "x0": 0, "x1": 1, "y0": 0, "y1": 0, "line": {"color": RED, "dash": "dash"}}
    ]
    if jump and jump.get("rpm") is not None:
        shapes.append(
            {
                "type": "line",
                "yref": "paper",
                "x0": jump["rpm"],
                "x1": jump["rpm"],
                "y0": 0,
                "y1": 1,
                "line": {"color": RED, "width": 1.5},
            }
        )
    del ok
    layout = {
        "height": 360,
        "margin": {"l": 70, "r": 20, "t": 40, "b": 80},
        "font": _FONT,
        "plot_bgcolor": "white",
        "title": {"text": title, "x": 0.01, "font": {"size": 14}},
        "xaxis": _axis("camshaft speed (rpm)", range=[lo - 0.02 * (hi - lo), hi + 0.02 * (hi - lo)]),
        "yaxis": _axis("min contact force (N)"),
        "shapes": shapes,
        "legend": {"orientation": "h", "y": -0.2, "yanchor": "top", "x": 0},
        "meta": {"cursor_axes": []},
    }
    return {"data": data, "layout": layout}


def overlay(before: Dict[str, Any], after: Dict[str, Any], rpm: float, residuals: Dict[str, Any]) -> Dict[str, Any]:
    """Synthesis, before and after: the rigid acceleration of both lifts and their residual vibration."""
    layout = _stacked(2, ["rigid acceleration", "residual (µm)"], 420, 0.0)
    layout["title"] = {"text": f"synthesis at {rpm:.6g} rpm: before and after", "x": 0.01, "font": {"size": 14}}
    layout["margin"]["t"] = 60
    layout["annotations"] = [
        {
            "text": residuals.get("text", ""),
            "xref": "paper",
            "yref": "paper",
            "x": 0,
            "y": 1.08,
            "showarrow": False,
            "xanchor": "left",
            "font": {"size": 11, "color": GREY},
        }
    ]
    data = [
        _line(before["theta_deg"], before["rigid_acceleration"], "before (design's lift)", 1, color=GREY, dash="dash"),
        _line(after["theta_deg"], after["rigid_acceleration"], "after (synthesized)", 1, color=BLUE),
        _line(before["theta_deg"], 1e6 * np.asarray(before["residual"]), "residual before", 2, color=GREY, dash="dash"),
        _line(after["theta_deg"], 1e6 * np.asarray(after["residual"]), "residual after", 2, color=GREEN),
    ]
    return {"data": data, "layout": layout}


def message(title: str, text: str, height: int = 300) -> Dict[str, Any]:
    """An empty figure that says why it is empty."""
    return {
        "data": [],
        "layout": {
            "height": height,
            "font": _FONT,
            "title": {"text": title, "x": 0.01, "font": {"size": 14}},
            "xaxis": {"visible": False},
            "yaxis": {"visible": False},
            "annotations": [{"text": text, "showarrow": False, "xref": "paper", "yref": "paper", "x": 0.5, "y": 0.5}],
            "meta": {"cursor_axes": []},
        },
    }
