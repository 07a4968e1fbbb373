# SPDX-License-Identifier: BSD-3-Clause
"""The design page: a Dash app (Flask underneath, Plotly.js served from the ``dash`` package itself, so
it works with no internet access) on a local server.

Each edit rebuilds the mechanism with the library's reader and redraws the kinematics and a quick
periodic steady state at once (one request); the background (camfollower.design.jobs) refines the
response to the studies' accuracy, runs the margin curve speed by speed and searches the first contact
loss, and the page polls for what it finished. The page's state (the config being edited) lives in
the browser tab, so two tabs edit two designs; the server keeps only each tab's warm start and
background results.
"""

from __future__ import annotations

import copy
import hmac
import math
import secrets
import time
import uuid
import warnings
from pathlib import Path
from typing import Any, Dict, List, Optional

from .. import _files
from ..config import load_config
from . import document as doc_
from . import figures as figs
from . import files as files_
from . import toml_text, views
from .jobs import Jobs

#: Margin curve: speeds between these fractions of the design speed, unless the config's [sweep] says.
MARGIN_RANGE = (0.5, 1.5)
MARGIN_SPEEDS = 11
#: A model whose quick response takes longer than this (s) gets its response in the background only,
#: so that each edit still redraws its kinematics at once (a large camshaft, a valve train).
QUICK_BUDGET = 0.5
#: A model with more DOFs than this starts with its response in the background (a flexible camshaft).
HEAVY_DOFS = 40
COOKIE = "camfollower_design_{port}"

_CURSOR_JS = """
function(angle) {
    if (angle === undefined || angle === null) { return window.dash_clientside.no_update; }
    const ids = ["fig-svaj", "fig-geometry", "fig-response", "fig-profile"];
    for (const id of ids) {
        const host = document.getElementById(id);
        const gd = host && host.querySelector(".js-plotly-plot");
        if (!gd || !gd.layout || !window.Plotly) { continue; }
        const meta = gd.layout.meta || {};
        const axes = meta.cursor_axes || [];
        const shapes = (gd.layout.shapes || []).filter(s => !s.name || s.name !== "cursor");
        for (const ax of axes) {
            shapes.push({type: "line", name: "cursor", xref: ax, yref: ax.replace("x", "y") + " domain",
                         x0: angle, x1: angle, y0: 0, y1: 1, line: {color: "#555555", width: 1, dash: "dot"}});
        }
        if (axes.length) { window.Plotly.relayout(gd, {shapes: shapes}); }
        const f = meta.follower;
        if (f) {
            const n = f.surface_x.length;
            const i = Math.round(angle / 360 * (n - 1));
            let x = [], y = [];
            if (f.roller_radius > 0) {
                for (let k = 0; k <= 72; k++) {
                    const t = 2 * Math.PI * k / 72;
                    x.push(f.reference_x[i] + f.roller_radius * Math.cos(t));
                    y.push(f.reference_y[i] + f.roller_radius * Math.sin(t));
                }
            } else {
                const j0 = Math.max(i - 1, 0), j1 = Math.min(i + 1, n - 1);
                let tx = f.surface_x[j1] - f.surface_x[j0], ty = f.surface_y[j1] - f.surface_y[j0];
                const l = Math.hypot(tx, ty) || 1, h = f.face_half_length;
                x = [f.surface_x[i] - h * tx / l, f.surface_x[i] + h * tx / l];
                y = [f.surface_y[i] - h * ty / l, f.surface_y[i] + h * ty / l];
            }
            const a = gd.data.findIndex(t => t.name === "follower at cursor");
            const b = gd.data.findIndex(t => t.name === "contact point, cam centre");
            if (a >= 0 && b >= 0) {
                window.Plotly.restyle(gd, {x: [x, [f.surface_x[i], 0]], y: [y, [f.surface_y[i], 0]]}, [a, b]);
            }
        }
    }
    return "" + angle;
}
"""

_HOVER_JS = """
function(a, b, c) {
    const t = window.dash_clientside.callback_context.triggered;
    if (!t || !t.length || !t[0].value || !t[0].value.points || !t[0].value.points.length) {
        return window.dash_clientside.no_update;
    }
    const x = t[0].value.points[0].x;
    return Math.round(((x % 360) + 360) % 360 * 2) / 2;
}
"""


def _dash():
    try:
        import dash
    except ImportError:  # pragma: no cover - the extra is missing
        raise ImportError(
            "the design page needs the 'design' extra (Dash, which ships Plotly.js): pip install 'camfollower[design]'"
        ) from None
    return dash


class DesignApp:
    """The page for one working folder: ``config`` (a path inside or outside it, or None for the
    paper's mechanism) is loaded first; files are read and written only inside ``root``."""

    def __init__(self, config: Optional[str] = None, *, root: str = ".", token: Optional[str] = None) -> None:
        self.root = Path(root).resolve()
        self.token = token or secrets.token_urlsafe(24)
        self.port = 0  # set by serve() once the socket is bound
        self.jobs = Jobs()
        self.initial = self._document(config)
        self.app = self._build()

    # -----------------------------------------------------------------------------------------------
    # Documents

    def _document(self, config: Optional[str]) -> Dict[str, Any]:
        """The page's state for a config file (or the default design)."""
        if config is None:
            data, base, source, digest = copy.deepcopy(doc_.DEFAULT_DESIGN), self.root, None, None
        else:
            path = Path(config).resolve()
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")  # force closure: shown on the page
                case = load_config(path)
            data, base, source, digest = case.data, path.parent, str(path), files_.digest(path)
        case = doc_.build(data, str(base))
        data = doc_.with_program_written_out(data, case)
        case = doc_.build(data, str(base))
        names = doc_.contact_names(case)
        if not names:
            raise ValueError(
                f"{source or 'the design'}: the mechanism has no cam contact: nothing to design on this page "
                "(add a [[contact]], docs/config.md)"
            )
        return self._state(data, base, source, digest, names, names[0] if names else None, case)

    def _state(self, data, base, source, digest, names, contact, case) -> Dict[str, Any]:
        fields = doc_.fields(data, case, contact) if contact else []
        return {
            "data": data,
            "base_dir": str(base),
            "source": source,
            "digest": digest,
            "contacts": names,
            "contact": contact,
            "shown": {f.path: f.value for f in fields},
            "paths": [f.path for f in fields],
            "computed": 0,
        }

    # -----------------------------------------------------------------------------------------------
    # Layout

    def _form(self, state: Dict[str, Any], case, errors: Optional[Dict[str, str]] = None) -> List[Any]:
        """The fields of `state`'s document by group (`errors`: messages to show at once)."""
        dash = _dash()
        html, dcc = dash.html, dash.dcc
        errors = errors or {}
        fields = doc_.fields(state["data"], case, state["contact"]) if state["contact"] else []
        groups: Dict[str, List[Any]] = {}
        for f in fields:
            fid = {"type": "field", "path": f.path}
            if f.kind == "choice":
                control = dcc.Dropdown(
                    id=fid, options=[{"label": c, "value": c} for c in f.choices], value=f.value, clearable=False
                )
            elif f.kind == "readonly":
                control = html.Span(f.value, className="readonly", id={"type": "readonly", "path": f.path})
            else:
                control = dcc.Input(id=fid, value=f.value, type="text", debounce=True, placeholder=f.unit)
            row = html.Div(
                [
                    html.Label(f.label, title=f"{f.path} ({f.unit})" if f.unit else f.path),
                    control,
                    html.Div(errors.get(f.path, ""), id={"type": "error", "path": f.path}, className="field-error"),
                ],
                className="field",
            )
            groups.setdefault(f.group, []).append(row)
        return [html.Details([html.Summary(g)] + rows, open=True, className="group") for g, rows in groups.items()]

    def _layout(self):
        dash = _dash()
        html, dcc = dash.html, dash.dcc
        state = copy.deepcopy(self.initial)
        case = doc_.build(state["data"], state["base_dir"])
        source = state["source"] or "the paper's mechanism (default design)"
        return html.Div(
            [
                dcc.Store(id="tab", data=uuid.uuid4().hex),
                dcc.Store(id="doc", data=state),
                dcc.Store(id="seen", data=-1),
                dcc.Store(id="reload", data=0),
                dcc.Interval(id="poll", interval=300, disabled=True),
                html.Div(
                    [
                        html.H1("camfollower design"),
                        html.Span(source, id="source"),
                        html.Div(id="status", className="status"),
                        html.Div(
                            [html.Span(id="bg-status"), html.Button("Cancel", id="cancel", n_clicks=0)],
                            className="bg",
                        ),
                    ],
                    className="header",
                ),
                html.Div(
                    [
                        html.Div(
                            [
                                html.Div(
                                    [
                                        html.Label("contact"),
                                        dcc.Dropdown(
                                            id="contact",
                                            options=state["contacts"],
                                            value=state["contact"],
                                            clearable=False,
                                        ),
                                    ],
                                    className="field",
                                ),
                                html.Div(self._form(state, case), id="form"),
                                html.Details(
                                    [
                                        html.Summary("Files (in the working folder)"),
                                        html.Div(str(self.root), className="readonly"),
                                        html.Div(
                                            [
                                                html.Label("config file"),
                                                dcc.Input(
                                                    id="config-name", type="text", value="design.toml", debounce=False
                                                ),
                                                html.Button("Save", id="save", n_clicks=0),
                                                html.Button("Open", id="open", n_clicks=0),
                                            ],
                                            className="field",
                                        ),
                                        html.Div(
                                            [
                                                html.Label("export name"),
                                                dcc.Input(id="export-name", type="text", value="cam", debounce=False),
                                                html.Button("Cam CSV", id="export-csv", n_clicks=0),
                                                html.Button("Cam DXF", id="export-dxf", n_clicks=0),
                                                html.Button("Figures", id="export-figures", n_clicks=0),
                                            ],
                                            className="field",
                                        ),
                                        html.Div(id="file-message", className="message"),
                                    ],
                                    open=True,
                                    className="group",
                                ),
                                html.Details(
                                    [
                                        html.Summary("Synthesis"),
                                        html.Div(
                                            "Redesign this contact's lift for the flexible mechanism at its speed "
                                            "(camfollower.synthesis; the config's [synthesis] table if it has one).",
                                            className="hint",
                                        ),
                                        html.Button("Synthesize", id="synthesize", n_clicks=0),
                                        html.Button("Use the synthesized lift", id="use-synthesis", n_clicks=0),
                                        html.Div(id="synthesis-message", className="message"),
                                    ],
                                    open=True,
                                    className="group",
                                ),
                            ],
                            className="left",
                        ),
                        html.Div(
                            [
                                html.Div(
                                    [
                                        html.Label("cam angle cursor (deg)"),
                                        dcc.Slider(
                                            id="cursor",
                                            min=0,
                                            max=360,
                                            step=0.5,
                                            value=0,
                                            marks={i: str(i) for i in range(0, 361, 45)},
                                            updatemode="drag",
                                        ),
                                        html.Span(id="cursor-shown", className="hint"),
                                    ],
                                    className="cursor",
                                ),
                                html.Div(
                                    [
                                        dcc.Graph(id="fig-svaj", config={"displaylogo": False}),
                                        dcc.Graph(id="fig-profile", config={"displaylogo": False}),
                                        dcc.Graph(id="fig-response", config={"displaylogo": False}),
                                        dcc.Graph(id="fig-geometry", config={"displaylogo": False}),
                                        dcc.Graph(
                                            id="fig-margin",
                                            config={"displaylogo": False},
                                            figure=figs.message("margin curve", "computed after each edit ..."),
                                        ),
                                        dcc.Graph(
                                            id="fig-synthesis",
                                            config={"displaylogo": False},
                                            figure=figs.message(
                                                "synthesis", "Synthesis (left, at the bottom): before and after"
                                            ),
                                        ),
                                    ],
                                    className="plots",
                                ),
                            ],
                            className="right",
                        ),
                    ],
                    className="main",
                ),
                html.Pre(id="computed", className="computed"),
            ]
        )

    # -----------------------------------------------------------------------------------------------
    # The app

    def _build(self):
        dash = _dash()
        from dash import ALL, Input, Output, State, ctx

        app = dash.Dash(
            __name__,
            title="camfollower design",
            serve_locally=True,
            assets_folder=str(Path(__file__).with_name("assets")),
            update_title=None,
        )
        app.layout = self._layout
        self._guard(app.server)

        app.clientside_callback(_CURSOR_JS, Output("cursor-shown", "children"), Input("cursor", "value"))
        app.clientside_callback(
            _HOVER_JS,
            Output("cursor", "value"),
            Input("fig-svaj", "hoverData"),
            Input("fig-geometry", "hoverData"),
            Input("fig-response", "hoverData"),
            prevent_initial_call=True,
        )

        @app.callback(
            Output("doc", "data"),
            Output({"type": "error", "path": ALL}, "children"),
            Output("fig-svaj", "figure"),
            Output("fig-profile", "figure"),
            Output("fig-geometry", "figure"),
            Output("fig-response", "figure"),
            Output("status", "children"),
            Output("poll", "disabled"),
            Output("computed", "children"),
            Input({"type": "field", "path": ALL}, "value"),
            Input("contact", "value"),
            Input("reload", "data"),
            State("doc", "data"),
            State("cursor", "value"),
            State("tab", "data"),
        )
        def edit(values, contact, _reload, state, cursor, tab):
            values = {i["id"]["path"]: v for i, v in zip(ctx.inputs_list[0], values)}
            ids = [o["id"]["path"] for o in ctx.outputs_list[1]]  # every field's error slot, read-only ones too
            return self.edit(state, values, ctx.triggered_id, contact, cursor or 0.0, tab, ids)

        @app.callback(
            Output("fig-response", "figure", allow_duplicate=True),
            Output("fig-margin", "figure"),
            Output("fig-synthesis", "figure"),
            Output("bg-status", "children"),
            Output("poll", "disabled", allow_duplicate=True),
            Output("seen", "data"),
            Input("poll", "n_intervals"),
            State("tab", "data"),
            State("seen", "data"),
            State("doc", "data"),
            State("cursor", "value"),
            prevent_initial_call=True,
        )
        def poll(_n, tab, seen, state, cursor):
            return self.poll(tab, seen, state, cursor or 0.0)

        @app.callback(
            Output("bg-status", "children", allow_duplicate=True),
            Input("cancel", "n_clicks"),
            State("tab", "data"),
            prevent_initial_call=True,
        )
        def cancel(_n, tab):
            self.jobs.cancel(tab)
            return "cancelled"

        @app.callback(
            Output("file-message", "children"),
            Input("save", "n_clicks"),
            Input("open", "n_clicks"),
            Input("export-csv", "n_clicks"),
            Input("export-dxf", "n_clicks"),
            Input("export-figures", "n_clicks"),
            State("config-name", "value"),
            State("export-name", "value"),
            State("doc", "data"),
            prevent_initial_call=True,
        )
        def file_action(_s, _o, _c, _d, _f, config_name, export_name, state):
            return self.file_action(ctx.triggered_id, config_name, export_name, state)

        @app.callback(
            Output("synthesis-message", "children"),
            Output("poll", "disabled", allow_duplicate=True),
            Input("synthesize", "n_clicks"),
            Input("use-synthesis", "n_clicks"),
            State("doc", "data"),
            State("tab", "data"),
            prevent_initial_call=True,
        )
        def synthesis_action(_s, _u, state, tab):
            return self.synthesis_action(ctx.triggered_id, state, tab)

        return app

    # -----------------------------------------------------------------------------------------------
    # Security: this page can edit and write files, so only its own tab may talk to it.

    def _guard(self, server) -> None:
        import flask

        @server.before_request
        def check():
            host = flask.request.host
            allowed_hosts = {f"127.0.0.1:{self.port}", f"localhost:{self.port}"}
            if host not in allowed_hosts:
                return flask.Response(
                    f"refused: this page answers only at http://127.0.0.1:{self.port} (Host {host!r})\n", 403
                )
            origin = flask.request.headers.get("Origin")
            if origin is not None and origin not in {f"http://{h}" for h in allowed_hosts}:
                return flask.Response(f"refused: a request from another origin ({origin})\n", 403)
            given = flask.request.args.get("token")
            if given is not None and hmac.compare_digest(given, self.token):
                # The token from the printed address becomes a cookie (this port's), and the address bar
                # loses it.
                response = flask.redirect("/", code=303)
                response.set_cookie(
                    COOKIE.format(port=self.port), self.token, httponly=True, samesite="Strict", path="/"
                )
                return response
            cookie = flask.request.cookies.get(COOKIE.format(port=self.port), "")
            if not hmac.compare_digest(cookie, self.token):
                return flask.Response(
                    "refused: open the page at the address `camfollower design` printed (it carries the token)\n",
                    403,
                )
            return None

    # -----------------------------------------------------------------------------------------------
    # Edits

    def _case(self, state):
        return doc_.build(state["data"], state["base_dir"])

    def edit(self, state, values, trigger, contact, cursor, tab, ids):
        dash = _dash()
        no = dash.no_update
        errors = {p: "" for p in ids}
        t0 = time.perf_counter()
        state = copy.deepcopy(state)
        changed = None
        if isinstance(trigger, dict) and trigger.get("type") == "field":
            path = trigger["path"]
            if path in values and values[path] != state["shown"].get(path):
                changed = path
        elif trigger == "contact" and contact != state["contact"]:
            changed = "contact"
        # A new document (Open, a synthesized lift) is drawn whatever the fields say; so is one whose
        # last edit was refused (the same text typed again is tried again).
        again = trigger == "reload" or state.get("refused")
        if changed is None and state.get("computed") and not again:
            raise dash.exceptions.PreventUpdate
        if changed == "contact":
            state["contact"] = contact
        elif changed is not None:
            state["shown"][changed] = values[changed]
            try:
                state["data"] = doc_.set_value(state["data"], changed, values[changed])
            except ValueError as e:
                errors[changed] = str(e)
                return self._refused(state, errors, ids, f"not updated: {e}", tab)
        try:
            case = self._case(state)
            k = views.kinematics(case, state["contact"])
        except ValueError as e:
            state = self._restructured(state)  # a law or type that was refused still brings its fields
            where = doc_.field_of_message(str(e), state["paths"]) or changed
            errors[where] = _clean(str(e))
            return self._refused(state, errors, ids, f"not updated: {_clean(str(e))}", tab)
        state["refused"] = False
        t_build = time.perf_counter()
        if k["check"]:
            where = doc_.field_of_message(k["check"], ids) or changed
            if where in errors:
                errors[where] = k["check"]
        t_kin = time.perf_counter()
        status = []
        closure = list(case.warnings)
        memo = self.jobs.tab(tab).memo
        quick = None
        response_figure = no
        heavy = len(case.mechanism.dof_names) > HEAVY_DOFS  # until a refined run says what it costs
        if memo.get("quick_seconds", QUICK_BUDGET * 2 if heavy else 0.0) <= QUICK_BUDGET and not k["check"]:
            try:
                quick = views.response(case, state["contact"], guess=_guess(memo, case), stop_at_loss=True)
                memo["orbit"], memo["dofs"] = quick.pop("orbit"), len(case.mechanism.dof_names)
                response_figure = figs.response(quick, k["rpm"], cursor, label=", quick: refining ...")
            except (ValueError, RuntimeError) as e:
                response_figure = figs.message("flexible response", _clean(str(e)))
        t_resp = time.perf_counter()
        if quick is not None:
            memo["quick_seconds"] = t_resp - t_kin
        elif k["check"]:
            response_figure = figs.message("flexible response", "not computed: the cam cannot be followed")
        fig_svaj = figs.svaj(k, cursor)
        fig_profile = figs.profile(k, cursor)
        fig_geometry = figs.geometry(k, cursor)
        t_fig = time.perf_counter()
        structure = [f.path for f in doc_.fields(state["data"], case, state["contact"])]
        if structure != state["paths"] or changed == "contact":
            new = self._state(
                state["data"],
                state["base_dir"],
                state["source"],
                state["digest"],
                state["contacts"],
                state["contact"],
                case,
            )
            new["computed"] = state["computed"]
            state = new
            dash.set_props("form", {"children": self._form(state, case)})
        state["computed"] += 1
        if not k["check"]:
            self._start_background(tab, case, state)
        else:
            self.jobs.start(tab, [], status="")
        timing = {
            "build_ms": 1e3 * (t_build - t0),
            "kinematics_ms": 1e3 * (t_kin - t_build),
            "response_ms": 1e3 * (t_resp - t_kin),
            "figures_ms": 1e3 * (t_fig - t_resp),
            "total_ms": 1e3 * (time.perf_counter() - t0),
            "computed": state["computed"],
            "rpm": k["rpm"],
        }
        status.append(f"updated in {timing['total_ms']:.0f} ms")
        if quick is None and not k["check"]:
            status.append("flexible response computed in the background (a heavy model)")
        if k["check"]:
            status.append(f"the cam cannot be followed: {k['check']}")
        status += [f"warning: {w}" for w in closure]
        return (
            state,
            [errors.get(p, "") for p in ids],
            *_changed(memo, {"svaj": fig_svaj, "profile": fig_profile, "geometry": fig_geometry}),
            response_figure,
            " · ".join(status),
            k["check"] is not None,
            _json(timing),
        )

    def _refused(self, state, errors, ids, status, tab):
        """The edit's answer when the design cannot be built: the message at its field, the figures
        left as they are (the status says so), no background work."""
        no = _dash().no_update
        state["refused"] = True
        self.jobs.start(tab, [], status="nothing computed: the design has an error (see the field it names)")
        status += " (the figures show the last design that worked)"
        if state["paths"] != ids:  # other fields now (a law, a type): a new form, the message in it
            _dash().set_props("form", {"children": self._form(state, None, errors)})
            return (state, [no] * len(ids), no, no, no, no, status, False, no)
        return (state, [errors.get(p, "") for p in ids], no, no, no, no, status, False, no)

    def _restructured(self, state):
        """`state` with its form rebuilt (in the browser too) when its data now has other fields than
        the form shows: a law or follower type changed, even if the design cannot be built."""
        fields = doc_.fields(state["data"], None, state["contact"])
        paths = [f.path for f in fields]
        if paths == state["paths"]:
            return state
        state = dict(state, paths=paths, shown={f.path: f.value for f in fields})
        return state

    # -----------------------------------------------------------------------------------------------
    # Background: refine, margin curve, first contact loss

    def _margin_speeds(self, state, rpm: float) -> List[float]:
        sweep = state["data"].get("sweep") or {}
        try:
            lo, hi, n = float(sweep["rpm_from"]), float(sweep["rpm_to"]), int(sweep.get("count", MARGIN_SPEEDS))
        except (KeyError, TypeError, ValueError):
            lo, hi, n = MARGIN_RANGE[0] * rpm, MARGIN_RANGE[1] * rpm, MARGIN_SPEEDS
        n = max(2, min(n, 41))
        return [lo + (hi - lo) * i / (n - 1) for i in range(n)]

    def _start_background(self, tab, case, state) -> None:
        contact = state["contact"]
        rpm = float(case.mechanism.camshaft_speed_rpm)
        speeds = self._margin_speeds(state, rpm)
        memo = self.jobs.tab(tab).memo

        def refine(results):
            r = views.response(case, contact, accuracy=views.REFINED_ACCURACY, guess=_guess(memo, case))
            memo["orbit"], memo["dofs"] = r.pop("orbit"), len(case.mechanism.dof_names)
            results["response"] = r
            # What a quick steady state would cost this model (decides the next edit's route).
            memo["quick_seconds"] = r["seconds"] * views.QUICK_STEPS / r["summary"]["steps_per_revolution"]
            if grooved:
                return f"response refined to {r['summary']['accuracy']:.1e} of peak (a grooved cam: no margin curve)"
            results["margin_speeds"] = speeds
            results["margin_rows"] = []
            return f"response refined to {r['summary']['accuracy']:.1e} of peak; margin curve ..."

        def at(rpm_i):
            def step(results):
                try:
                    row = views.margin_point(case, rpm_i, contact, guess=results.get("margin_orbit"))
                    results["margin_orbit"] = row.pop("orbit")
                except (ValueError, RuntimeError) as e:
                    row = {"rpm": rpm_i, "error": str(e)}
                results["margin_rows"].append(_row_json(row))
                return f"margin curve: {len(results['margin_rows'])} of {len(speeds)} speeds"

            return step

        def first_loss(results):
            from ..speed import jump_speed

            try:
                with warnings.catch_warnings(record=True) as caught:
                    warnings.simplefilter("always")
                    j = jump_speed(case.mechanism, (speeds[0], speeds[-1]), contact=contact)
                notes = "".join(f"; {w.message}" for w in caught)
                results["jump"] = {
                    "rpm": float(j.rpm),
                    "message": notes,
                    # Every speed the search ran: a dip narrower than the margin curve's spacing shows.
                    "scan": [_row_json(r) for r in j.margin],
                    "windows": [[w.start_rpm, w.end_rpm] for w in j.windows],
                }
                return f"first contact loss at {j.rpm:.5g} rpm (the jump-speed search){notes}"
            except ValueError as e:
                results["jump"] = {"rpm": None, "message": _clean(str(e))}
                return _clean(str(e))

        grooved = views.contact_of(case, contact).get("groove") is not None
        # A form-closed (grooved) cam has no margin against contact loss to scan.
        steps = [refine] + ([] if grooved else [at(s) for s in speeds] + [first_loss])
        self.jobs.start(tab, steps, status="refining the response ...")

    def poll(self, tab, seen, state, cursor):
        dash = _dash()
        no = dash.no_update
        snap = self.jobs.snapshot(tab)
        if snap["version"] == seen:
            if not snap["busy"]:
                return no, no, no, no, True, seen
            raise dash.exceptions.PreventUpdate
        res = snap["results"]
        response = no
        rpm = None
        try:
            rpm = float(doc_.build(state["data"], state["base_dir"]).mechanism.camshaft_speed_rpm)
        except ValueError:
            pass
        if "response" in res and rpm is not None:
            reached = res["response"]["summary"].get("accuracy_reached", True)
            label = ", refined" if reached else f", NOT refined to {views.REFINED_ACCURACY:g}: the finest step allowed"
            response = figs.response(res["response"], rpm, cursor, label=label)
        margin = no
        if "margin_speeds" in res:
            margin = figs.margin(res.get("margin_rows", []), res["margin_speeds"], res.get("jump"))
        synthesis = no
        if "synthesis" in res:
            s = res["synthesis"]
            synthesis = figs.overlay(s["before"], s["after"], s["rpm"], s)
        status = snap["status"] + (" ..." if snap["busy"] and not snap["status"].endswith("...") else "")
        return response, margin, synthesis, status, not snap["busy"], snap["version"]

    # -----------------------------------------------------------------------------------------------
    # Files

    def file_action(self, trigger, config_name, export_name, state):
        try:
            if trigger == "save":
                path = files_.save_config(
                    self.root,
                    config_name,
                    state["data"],
                    Path(state["base_dir"]),
                    state["source"],
                    state["digest"],
                )
                new = dict(state, source=str(path), digest=files_.digest(path), base_dir=str(path.parent))
                new["data"] = files_.rebase(state["data"], Path(state["base_dir"]), path.parent)
                _dash().set_props("doc", {"data": new})
                _dash().set_props("source", {"children": str(path)})
                return f"saved {path}"
            if trigger == "open":
                path = files_.inside(self.root, config_name, "open", files_.CONFIG_SUFFIX)
                new = self._document(str(path))
                new["computed"] = state.get("computed", 0)  # the count of drawings goes on (reload redraws)
                case = doc_.build(new["data"], new["base_dir"])
                dash = _dash()
                dash.set_props("doc", {"data": new})
                dash.set_props("form", {"children": self._form(new, case)})
                dash.set_props("contact", {"options": new["contacts"], "value": new["contact"]})
                dash.set_props("source", {"children": str(path)})
                dash.set_props("reload", {"data": time.time()})
                return f"opened {path}"
            return self._export(trigger, export_name, state)
        except (ValueError, OSError, RuntimeError) as e:
            return f"not done: {_clean(str(e))}"

    def _export(self, trigger, name, state):
        from .. import export as ex

        case = self._case(state)
        c = views.contact_of(case, state["contact"])
        protect = [state["source"]] if state["source"] else []
        if trigger in ("export-csv", "export-dxf"):
            suffix = ".csv" if trigger == "export-csv" else ".dxf"
            path = files_.inside(self.root, f"{name}{suffix}", "export")
            if ex.is_barrel(c["follower"]):
                raise ValueError(
                    "export: a barrel cam's groove is exported by `camfollower export` (its roller and clearance)"
                )
            writer = ex.write_csv if suffix == ".csv" else ex.write_dxf
            _files.check_target(str(path), protect=protect)
            writer(str(path), c["follower"], c["program"], points=3600, unit="mm", frame_angle=c["frame_angle"])
            return f"cam surface of contact '{c['name']}' (3600 points, mm) -> {path}"
        if trigger == "export-figures":
            from .. import cli

            folder = files_.inside(self.root, f"{name}_figures", "export")
            folder.mkdir(exist_ok=True)
            config = files_.inside(self.root, f"{name}_figures/design.toml", "export")
            _files.write_text(
                config, toml_text.dumps(files_.rebase(state["data"], Path(state["base_dir"]), folder)), protect=protect
            )
            summary = cli.figures(str(config), str(folder))
            return f"figures of the design ({len(summary.get('files', [])) or 'all'}) and design.toml -> {folder}"
        raise ValueError(f"unknown action {trigger!r}")  # pragma: no cover

    # -----------------------------------------------------------------------------------------------
    # Synthesis

    def synthesis_action(self, trigger, state, tab):
        memo = self.jobs.tab(tab).memo
        dash = _dash()
        if trigger == "use-synthesis":
            program = memo.get("synthesized")
            if program is None:
                return "nothing to use yet: run Synthesize first", dash.no_update
            name = doc_.program_name(state["data"], state["contact"])
            if not name:
                return "this contact's program is the preset's own: it cannot be replaced here", dash.no_update
            data = doc_.with_program(
                state["data"], name, program, not doc_.translating(state["data"], state["contact"])
            )
            case = doc_.build(data, state["base_dir"])
            new = self._state(
                data, state["base_dir"], state["source"], state["digest"], state["contacts"], state["contact"], case
            )
            new["computed"] = state.get("computed", 0)
            dash.set_props("doc", {"data": new})
            dash.set_props("form", {"children": self._form(new, case)})
            dash.set_props("reload", {"data": time.time()})
            return (
                f"program '{name}' replaced by the synthesized lift (its segments are now spline tables)",
                dash.no_update,
            )
        try:
            case = self._case(state)
        except ValueError as e:
            return f"not started: {_clean(str(e))}", dash.no_update
        contact = state["contact"]

        def run(results):
            from .. import synthesis
            from ..studies import synthesis_settings

            m = case.mechanism
            settings = synthesis_settings(
                state["data"].get("synthesis"), contacts=m.contact_names, dofs=list(m.dof_names)
            )
            start = settings.pop("start", "program")
            settings["contact"] = contact
            own = views.contact_of(case, contact)
            if start != "program":
                settings["start"] = synthesis.with_laws(own["program"], start)
            result = synthesis.synthesize(m, workers=1, **settings)
            memo["synthesized"] = result.program
            # The same mechanism with the new lift, for the overlay.
            data, name = state["data"], doc_.program_name(state["data"], contact)
            after_case = doc_.build(
                doc_.with_program(data, name, result.program, not doc_.translating(data, contact)), state["base_dir"]
            )
            before = views.response(case, contact, accuracy=views.REFINED_ACCURACY)
            after = views.response(after_case, contact, accuracy=views.REFINED_ACCURACY)
            before.pop("orbit"), after.pop("orbit")
            rb, ra = before["summary"]["dwell_residual"], after["summary"]["dwell_residual"]
            results["synthesis"] = {
                "before": before,
                "after": after,
                "rpm": float(m.camshaft_speed_rpm),
                "text": f"dwell residual {1e6 * rb:.3g} -> {1e6 * ra:.3g} µm p-p ({rb / ra if ra > 0 else math.inf:.3g}x lower); "
                f"{result.summary().get('evaluations', '?')} steady states",
            }
            return "synthesis done: see the before/after figure; 'Use the synthesized lift' puts it in the design"

        self.jobs.start(tab, [run], status="synthesizing (tens of seconds on the paper's mechanism) ...")
        return "synthesizing ... (Cancel stops it after its current run)", False


def _changed(memo, figures: Dict[str, Any]) -> List[Any]:
    """The figures that differ from what this tab shows, the others as no_update: a speed changes
    neither the profile nor the pressure angle, and the browser need not draw them again."""
    out = []
    for name, figure in figures.items():
        key = hash(_json(figure))
        out.append(_dash().no_update if memo.get(f"shown_{name}") == key else figure)
        memo[f"shown_{name}"] = key
    return out


def _guess(memo, case):
    """The tab's last orbit as a warm start, when it fits the mechanism (the same DOFs)."""
    return memo.get("orbit") if memo.get("dofs") == len(case.mechanism.dof_names) else None


def _clean(message: str) -> str:
    return message[len("<dict>: ") :] if message.startswith("<dict>: ") else message


def _row_json(row: Dict[str, Any]) -> Dict[str, Any]:
    keep = ("rpm", "min_force_N", "min_force_angle_deg", "contact_lost", "first_loss_angle_deg", "accuracy", "error")
    return {k: row[k] for k in keep if k in row}


def _json(value) -> str:
    import json

    return json.dumps(value, default=float)


def serve(
    config: Optional[str] = None,
    *,
    port: int = 0,
    root: str = ".",
    open_browser: bool = True,
    token: Optional[str] = None,
    ready=None,
) -> None:
    """Start the page on 127.0.0.1 (only) at `port` (0: a free one), print its address (with the
    token) and open it in the browser; serve until interrupted. ``ready(url, server)`` is called once
    the socket is bound (tests use it)."""
    import logging

    from werkzeug.serving import make_server

    logging.getLogger("werkzeug").setLevel(logging.WARNING)  # not a line per request
    page = DesignApp(config, root=root, token=token)
    server = make_server("127.0.0.1", port, page.app.server, threaded=True)
    page.port = server.server_port
    url = f"http://127.0.0.1:{page.port}/?token={page.token}"
    print(f"camfollower design: {page.initial['source'] or 'the default design'} at {url}", flush=True)
    print("  (local only; Ctrl-C stops it)", flush=True)
    if ready is not None:
        ready(url, server)
    if open_browser:
        import webbrowser

        webbrowser.open(url)
    try:
        server.serve_forever()
    except KeyboardInterrupt:
        pass
    finally:
        server.server_close()
        page.jobs.stop()
