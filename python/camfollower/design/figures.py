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


#: Significant digits of the numbers drawn: a tenth of a pixel on any screen, and half the JSON of full
#: precision (what each redraw sends and the browser parses).
DIGITS = 7


def _list(x) -> List[Optional[float]]:
    """A JSON array to DIGITS significant digits of its largest value; NaN as null (a gap)."""
    a = np.asarray(x, dtype=float)
    finite = np.isfinite(a)
    peak = float(np.max(np.abs(a[finite]))) if finite.any() else 0.0
    if peak > 0.0:
        a = np.round(a, DIGITS - 1 - int(math.floor(math.log10(peak))))
    return [v if f else None for v, f in zip(a.tolist(), finite.tolist())]


def _grid(x) -> Dict[str, float]:
    """An evenly spaced x as Plotly's x0 and dx (no array to send)."""
    a = np.asarray(x, dtype=float)
    return {"x0": float(a[0]), "dx": float(a[1] - a[0])}


def _axis(title: str, **extra) -> Dict[str, Any]:
    return {"title": {"text": title}, "showgrid": True, "gridcolor": "#e5e5e5", "zeroline": False, **extra}


def _angle_axis(title: str = "") -> Dict[str, Any]:
    return _axis(title, range=[0, 360], tickvals=list(range(0, 361, 45)))


def _cursor_shapes(axes: Sequence[str], cursor_deg: float) -> List[Dict[str, Any]]:
    return [
        {
            "type": "line",
            "name": "cursor",  # the page's cursor script replaces the shapes of this name
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
        "margin": {"l": 75, "r": 30, "t": 30, "b": 110},
        "font": _FONT,
        "showlegend": True,
        # Below the cam-angle axis title: 60 px under the plot area, whatever the figure's height.
        "legend": {"orientation": "h", "y": -60.0 / (height - 30 - 110), "yanchor": "top", "x": 0},
        "modebar": {"orientation": "v"},
        "plot_bgcolor": "white",
        "hovermode": "closest",
    }
    axes = []
    for i in range(rows):
        n = "" if i == 0 else str(i + 1)
        top = 1.0 - i * (h + gap)
        layout[f"yaxis{n}"] = _axis(titles[i], domain=[top - h, top], anchor=f"x{n}")
        # The same fixed range on every subplot rather than linked axes ("matches"): a third cheaper to
        # draw again, and the cursor links them.
        layout[f"xaxis{n}"] = _angle_axis("cam angle θ (deg)" if i == rows - 1 else "")
        layout[f"xaxis{n}"].update(anchor=f"y{n}", showticklabels=i == rows - 1)
        axes.append(f"x{n}")
    layout["shapes"] = _cursor_shapes(axes, cursor_deg)
    layout["meta"] = {"cursor_axes": axes}
    return layout


def _line(x, y, name: str, axis: int = 1, even: bool = False, **style) -> Dict[str, Any]:
    """A line; ``even``: x is evenly spaced, sent as x0 and dx."""
    n = "" if axis == 1 else str(axis)
    return {
        "type": "scatter",
        "mode": "lines",
        **(_grid(x) if even else {"x": _list(x)}),
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
        _line(x, k["lift"], "lift", 1, True, color=BLUE),
        _line(x, k["velocity"], "velocity", 2, True, color=BLUE),
        _line(x, k["acceleration"], "acceleration", 3, True, color=BLUE),
        _line(x, k["jerk"], "jerk", 4, True, color=BLUE),
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


#: Colour classes of the profile's outline (a line per class draws in a fraction of the time of a
#: marker per point).
CLASSES = 12


def _coloured_outline(x, y, value) -> List[Dict[str, Any]]:
    """The outline x, y coloured by `value` (deg) on Viridis: one line per class of CLASSES, each
    joined to its neighbours' points, and a colour bar."""
    value = np.asarray(value, dtype=float)
    top = max(30.0, float(np.nanmax(value)) if value.size else 30.0)
    cls = np.minimum((value / top * CLASSES).astype(int), CLASSES - 1)
    traces = []
    for c in range(CLASSES):
        mine = cls == c
        keep = mine | np.roll(mine, 1)  # the next point too: no gap where the class changes
        if not mine.any():
            continue
        lo, hi = top * c / CLASSES, top * (c + 1) / CLASSES
        # Only this class's runs of points, a null between runs (a gap): no array of nulls to send.
        gaps = np.flatnonzero(np.diff(keep.astype(int)) == -1) + 1
        idx = np.flatnonzero(keep)
        xs, ys = np.asarray(x, dtype=float)[idx], np.asarray(y, dtype=float)[idx]
        breaks = np.searchsorted(idx, gaps[gaps < len(keep)])
        xs, ys = np.insert(xs, breaks, np.nan), np.insert(ys, breaks, np.nan)
        traces.append(
            {
                "type": "scatter",
                "mode": "lines",
                "x": _list(xs),
                "y": _list(ys),
                "name": f"|α| {lo:.0f}-{hi:.0f}°",
                "showlegend": False,
                "hovertemplate": f"|α| {lo:.1f} to {hi:.1f}°<extra></extra>",
                "line": {"width": 3, "color": _viridis((c + 0.5) / CLASSES)},
            }
        )
    traces.append(  # the colour bar, on two invisible points
        {
            "type": "scatter",
            "mode": "markers",
            "x": [None, None],
            "y": [None, None],
            "name": "cam surface",
            "hoverinfo": "skip",
            "marker": {
                "color": [0.0, top],
                "colorscale": "Viridis",
                "cmin": 0.0,
                "cmax": top,
                "colorbar": {"title": {"text": "|α| (deg)"}, "thickness": 12},
            },
        }
    )
    return traces


_VIRIDIS = (
    "#440154",
    "#482878",
    "#3e4989",
    "#31688e",
    "#26828e",
    "#1f9e89",
    "#35b779",
    "#6ece58",
    "#b5de2b",
    "#fde725",
)


def _viridis(t: float) -> str:
    """Viridis at t in [0, 1], interpolated between its ten published stops."""
    t = min(max(t, 0.0), 1.0) * (len(_VIRIDIS) - 1)
    i = min(int(t), len(_VIRIDIS) - 2)
    a, b = _VIRIDIS[i], _VIRIDIS[i + 1]
    rgb = [round(int(a[j : j + 2], 16) * (1 - (t - i)) + int(b[j : j + 2], 16) * (t - i)) for j in (1, 3, 5)]
    return "#" + "".join(f"{v:02x}" for v in rgb)


def profile(k: Dict[str, Any], cursor_deg: float = 0.0) -> Dict[str, Any]:
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
        "modebar": {"orientation": "v"},
        "meta": {"cursor_axes": []},
    }
    if p is None:
        layout["title"]["text"] = "a barrel cam: no plate profile (see the developed groove: camfollower figures)"
        return {"data": [], "layout": layout}
    colour = np.abs(k["pressure_angle_deg"])
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
        *_coloured_outline(p["surface_x"], p["surface_y"], colour),
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
        _line(x, k["pressure_angle_deg"], "pressure angle", 1, True, color=BLUE),
        _line([0, 360], [max_pressure_angle_deg] * 2, f"limit ±{max_pressure_angle_deg:g}°", 1, color=RED, dash="dash"),
        _line([0, 360], [-max_pressure_angle_deg] * 2, "", 1, color=RED, dash="dash"),
        _line(x, rho, "surface radius (gap beyond ±10 r_b)", 2, True, color=BLUE),
        _line([0, 360], [0, 0], "0: cusp / undercut", 2, color=RED, dash="dash"),
    ]
    data[2]["showlegend"] = False
    return {"data": data, "layout": layout}


def response(r: Dict[str, Any], rpm: float, cursor_deg: float = 0.0, label: str = "") -> Dict[str, Any]:
    """The flexible response at the camshaft's speed: the follower's acceleration against the rigid
    one, the contact force with contact loss shaded, and the residual vibration in the dwells."""
    u = r["unit"]
    titles = [f"accel. ({u}/s²)", "force (N)", f"residual ({'µm' if u == 'm' else 'µrad'})"]
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
        _line(x, r["acceleration"], f"follower '{r['dof']}' (flexible)", 1, color=BLUE),
        _line(x, r["rigid_acceleration"], "rigid ω²h″", 1, color="black", dash="dash", width=1),
        _line(x, r["force"], "contact force" if r.get("outer_force") is None else "lifting flank force", 2, color=BLUE),
        _line(x, 1e6 * np.asarray(r["residual"], dtype=float), "residual vibration (dwells)", 3, color=GREEN),
    ]
    if r.get("outer_force") is not None:  # a groove: the other flank pushes the other way
        data.insert(3, _line(x, -np.asarray(r["outer_force"]), "outer flank force (negative)", 2, color=ORANGE))
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
        free = "roller free in the groove" if r.get("outer_force") is not None else "contact lost"
        data.append(_line([None], [None], free, 2, color=RED, width=8))
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
            "align": "left",
            "font": {"size": 11, "color": GREY},
        }
    ]
    return {"data": data, "layout": layout}


def _speeds(rows: Sequence[Dict[str, Any]], name: str, mode: str, **style) -> Dict[str, Any]:
    """The smallest contact force of `rows` (steady states) against their speed."""
    return {
        "type": "scatter",
        "mode": mode,
        "x": [r["rpm"] for r in rows],
        "y": [r["min_force_N"] for r in rows],
        "name": name,
        **style,
    }


def margin(
    rows: Sequence[Dict[str, Any]], speeds: Sequence[float], jump: Optional[Dict[str, Any]] = None
) -> Dict[str, Any]:
    """Minimum contact force of the steady state against camshaft speed (computed so far), contact loss
    marked, and the first contact loss found by the jump-speed search."""
    done = [r for r in rows if "min_force_N" in r]
    bad = [r for r in done if r.get("contact_lost")]
    lo, hi = (min(speeds), max(speeds)) if speeds else (0, 1)
    title = f"margin curve: {len(done)} of {len(speeds)} speeds"
    if jump and jump.get("rpm") is not None:
        title += f"; first contact loss at {jump['rpm']:.5g} rpm"
    elif jump and jump.get("message"):
        title += f"; {jump['message']}"
    scan = [r for r in (jump or {}).get("scan", []) if "min_force_N" in r]
    data = [
        # The jump-speed search's own speeds: it refines every dip, so a narrow resonance shows.
        _speeds(
            scan, "the jump-speed search's speeds", "markers", marker={"color": GREY, "size": 4}, showlegend=bool(scan)
        ),
        _speeds(done, "min contact force", "lines+markers", line={"color": BLUE, "width": 1.4}),
        _speeds(bad, "contact lost", "markers", marker={"color": RED, "size": 10, "symbol": "x"}),
    ]
    shapes = [
        {"type": "line", "xref": "paper", "x0": 0, "x1": 1, "y0": 0, "y1": 0, "line": {"color": RED, "dash": "dash"}}
    ]
    for start, end in (jump or {}).get("windows", []):  # contact lost over these speeds
        shapes.append(
            {
                "type": "rect",
                "yref": "paper",
                "x0": start,
                "x1": end if end is not None and math.isfinite(end) else hi,
                "y0": 0,
                "y1": 1,
                "fillcolor": RED,
                "opacity": 0.15,
                "line": {"width": 0},
            }
        )
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
    layout = {
        "height": 360,
        "margin": {"l": 70, "r": 20, "t": 40, "b": 80},
        "font": _FONT,
        "plot_bgcolor": "white",
        "title": {"text": title, "x": 0.01, "font": {"size": 14}},
        "xaxis": _axis("camshaft speed (rpm)", range=[lo - 0.02 * (hi - lo), hi + 0.02 * (hi - lo)]),
        "yaxis": _axis("min contact force (N)"),
        "shapes": shapes,
        "legend": {"orientation": "h", "y": -0.25, "yanchor": "top", "x": 0},
        "modebar": {"orientation": "v"},
        "meta": {"cursor_axes": []},
    }
    return {"data": data, "layout": layout}


def overlay(before: Dict[str, Any], after: Dict[str, Any], rpm: float, residuals: Dict[str, Any]) -> Dict[str, Any]:
    """Synthesis, before and after: the rigid acceleration of both lifts and their residual vibration."""
    u = before["unit"]
    layout = _stacked(2, [f"rigid accel. ({u}/s²)", f"residual ({'µm' if u == 'm' else 'µrad'})"], 460, 0.0)
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
