"""The configuration reference (``docs/configuration.md``), generated from the schema.

Every table of a run file (``rocking run``, ``report``, ``animate``), of a stack file
(``[[blocks]]``, ``rocking run``) and of the three study files
(``rocking design``, ``fragility``, ``spectrum``) is read off the pydantic models that validate
them: key, type, default and allowed values come from the models themselves, so the page
cannot drift from what the loader accepts. Only the unit and the meaning of each key are written
here, in :data:`MEANING`; a test fails when a key has none, or when the committed page is not
what this module writes.

    python -m rocking.cli.config_reference --out docs/configuration.md
"""

from __future__ import annotations

import argparse
import math
import types
import typing
from collections.abc import Iterator
from pathlib import Path
from typing import Any, Literal

from pydantic import BaseModel
from pydantic.fields import FieldInfo
from pydantic_core import PydanticUndefined

from ..io import config as run_config
from . import studies

__all__ = ["MEANING", "TABLES", "reference", "rows"]

#: (unit, meaning) of every key, by "<model>.<key>".
MEANING: dict[str, tuple[str, str]] = {
    # the tables of a file
    "Config.statue": ("", "the block that rocks"),
    "Config.pedestal": ("", "the squat block under it, which slides on the floor; omitted: the statue stands "
                            "on the floor"),
    "Config.motion": ("", "the floor motion: a record, a harmonic motion or a pulse"),
    "Config.simulation": ("", "run length, model options and solver tolerances"),
    "StackConfig.blocks": ("", "the blocks from the floor up, one [[blocks]] table each (at least one)"),
    "StackConfig.interfaces": ("", "the contacts from the floor up, one [[interfaces]] table under each block: "
                                   "floor–block 1, block 1–block 2, …"),
    "StackConfig.motion": ("", "the floor motion, as in run files"),
    "StackConfig.simulation": ("", "as in run files, but normal_force and impact keep their defaults (a stack "
                                   "has its own contact model)"),
    "_Study.statue": ("", "the block that rocks"),
    "_Study.pedestal": ("", "its pedestal (needed by the design; optional elsewhere)"),
    "_Study.simulation": ("", "model options and tolerances (not duration nor free_time_limit: the study's "
                              "free_time caps each run)"),
    "DesignStudy.motions": ("", "the motions every candidate must survive"),
    "DesignStudy.design": ("", "the candidates and the limits"),
    "FragilityStudy.fragility": ("", "the record set, the intensity levels and the fit"),
    "SpectrumStudy.spectrum": ("", "the motions, frequencies and amplitudes scanned"),
    # [statue]
    "StatueConfig.width": ("m", "B, the width of the statue's base"),
    "StatueConfig.height": ("m", "H, the height of the statue"),
    "StatueConfig.mass": ("kg", "the statue's mass"),
    "StatueConfig.restitution": ("–", "r in θ̇⁺ = r θ̇⁻; omitted: Housner's 1 − 1.5 sin²α"),
    "StatueConfig.friction": ("–", "friction under the statue (on the floor, or on the pedestal's top); "
                                   "omitted: it never slides"),
    # [pedestal]
    "PedestalConfig.mass": ("kg", "the pedestal's mass"),
    "PedestalConfig.friction": ("–", "friction of the pedestal on the floor"),
    "PedestalConfig.width": ("m", "the pedestal's width (for the uplift check only)"),
    "PedestalConfig.height": ("m", "the pedestal's height (for the uplift check only)"),
    # [[blocks]], [[interfaces]]
    "BlockConfig.name": ("", "names the block in the summary, the tables and the CSV columns (each its own); "
                             "omitted: \"block k\""),
    "BlockConfig.width": ("m", "B, the width of the block"),
    "BlockConfig.height": ("m", "H, the height of the block"),
    "BlockConfig.mass": ("kg", "the block's mass"),
    "BlockConfig.inertia": ("kg·m²", "moment of inertia about its centre of mass; omitted: a uniform block, "
                                     "m (B² + H²)/12"),
    "BlockConfig.offset": ("m", "its centre relative to the centre of the block below (block 1: to the floor's "
                                "origin), towards +x; the two must overlap: |offset| < (B + B below)/2"),
    "InterfaceConfig.friction": ("–", "Coulomb friction between the block and what it stands on; omitted: it "
                                      "never slips"),
    "InterfaceConfig.restitution": ("–", "r: relative angular velocity after/before an impact on the block's other "
                                         "corner; omitted: a plastic impact, which gives Housner's value. Under a "
                                         "block that carries others flat and stuck it is the r of the body they "
                                         "make (docs/theory/stack.md §6)"),
    # friction tables
    "FrictionConfig.static": ("–", "μs, static Coulomb friction"),
    "FrictionConfig.kinetic": ("–", "μk ≤ μs, kinetic Coulomb friction; omitted: μk = μs"),
    # [motion], each kind
    "HarmonicConfig.kind": ("", "\"harmonic\""),
    "HarmonicConfig.amplitude": ("m/s²", "A (negative reverses the direction)"),
    "HarmonicConfig.frequency": ("Hz", "f; the motion lasts cycles/f"),
    "HarmonicConfig.cycles": ("–", "number of cycles"),
    "HarmonicConfig.form": ("", "A·cos ωt (jumps to A at t = 0⁺) or A·sin ωt (starts from zero)"),
    "HarmonicConfig.angular_frequency": ("rad/s", "ω for the waveform (e.g. the paper's 7.53); omitted: 2πf"),
    "RecordConfig.kind": ("", "\"record\""),
    "RecordConfig.path": ("", "a file (relative to the config's folder) or a bundled record's name"),
    "RecordConfig.scale": ("–", "factor on the recorded acceleration (or give pga)"),
    "RecordConfig.pga": ("m/s²", "scale the record to this peak acceleration (or give scale)"),
    "RecordConfig.units": ("", "units of a file that does not state them: g, cm/s2 (gal), m/s2, mm/s2"),
    "RecordConfig.units_override": ("", "use units even where the file's header states others"),
    "RecordConfig.format": ("", "force the reader: peer (at2), esm (itaca), two-column (2col); omitted: detected"),
    "RecordConfig.vertical_path": ("", "the vertical component, on the same samples"),
    "RecordConfig.vertical_units": ("", "units of the vertical component's file, as units"),
    "SinePulseConfig.kind": ("", "\"pulse\""),
    "SinePulseConfig.shape": ("", "one-sine pulse a_p·sin(ωt + ψ)"),
    "SinePulseConfig.amplitude": ("m/s²", "a_p"),
    "SinePulseConfig.frequency": ("Hz", "f = ω/2π"),
    "SinePulseConfig.phase": ("rad", "ψ"),
    "CosinePulseConfig.kind": ("", "\"pulse\""),
    "CosinePulseConfig.shape": ("", "one-cosine pulse a_p·cos ωt"),
    "CosinePulseConfig.amplitude": ("m/s²", "a_p"),
    "CosinePulseConfig.frequency": ("Hz", "f = ω/2π"),
    "RectanglePulseConfig.kind": ("", "\"pulse\""),
    "RectanglePulseConfig.shape": ("", "rectangular pulse"),
    "RectanglePulseConfig.amplitude": ("m/s²", "its acceleration"),
    "RectanglePulseConfig.width": ("s", "its duration"),
    "RickerPulseConfig.kind": ("", "\"pulse\""),
    "RickerPulseConfig.shape": ("", "Ricker wavelet"),
    "RickerPulseConfig.amplitude": ("m/s²", "its peak"),
    "RickerPulseConfig.frequency": ("Hz", "its central frequency"),
    "RickerPulseConfig.center": ("s", "time of the peak; omitted: 1.5/f"),
    # [simulation]
    "SimulationConfig.duration": ("s", "simulated time; omitted: the motion, then free motion until everything "
                                       "is at rest (docs/verdicts.md)"),
    "SimulationConfig.free_time_limit": ("s", "longest free motion after the floor stops"),
    "SimulationConfig.max_samples": ("–", "saved samples a run may hold; a bigger run is refused (docs/limits.md)"),
    "SimulationConfig.gravity": ("m/s²", "g"),
    "SimulationConfig.normal_force": ("", "the full floor normal force, or the paper's N = M g"),
    "SimulationConfig.impact": ("", "Coulomb-bounded momentum impact, or the paper's θ̇⁺ = r θ̇⁻"),
    "SimulationConfig.rtol": ("–", "relative tolerance of the Runge–Kutta error control"),
    "SimulationConfig.atol": ("m, rad, m/s, rad/s", "absolute tolerance"),
    "SimulationConfig.max_step": ("s", "largest step"),
    "SimulationConfig.save_dt": ("s", "spacing of the saved series; omitted: the record's step, or 0.01 s"),
    "SimulationConfig.rest_velocity": ("rad/s", "|θ̇⁺| below which an impact leaves the statue at rest"),
    "SimulationConfig.stop_at_edge": ("", "stacks: stop, undetermined, when a sliding block reaches the edge of the "
                                          "one below (default: follow it past the edge)"),
    "SimulationConfig.max_events": ("–", "stop with status max_events after this many events"),
    # grids
    "GridConfig.start": ("as the key", "first value"),
    "GridConfig.stop": ("as the key", "last value (included)"),
    "GridConfig.num": ("–", "number of values"),
    "GridConfig.spacing": ("", "even steps, or even ratios"),
    # [motions] of a design study
    "MotionSetConfig.records": ("", "record files or bundled names"),
    "MotionSetConfig.pga": ("m/s²", "scale every record to this PGA"),
    "MotionSetConfig.pgv": ("m/s", "scale every record to this PGV"),
    "MotionSetConfig.scale": ("–", "or multiply every record by this factor"),
    "MotionSetConfig.family": ("", "a harmonic or pulse family instead of records"),
    "MotionSetConfig.amplitude": ("m/s²", "the family's amplitudes"),
    "MotionSetConfig.frequency": ("Hz", "the family's frequencies"),
    "MotionSetConfig.cycles": ("–", "cycles of a harmonic family"),
    "MotionSetConfig.form": ("", "waveform of a harmonic family"),
    # [design]
    "DesignConfig.mu_s": ("–", "candidate static friction of the pedestal's floor face (each ≥ 0)"),
    "DesignConfig.mu_k": ("–", "a fixed kinetic friction (capped at each μs)"),
    "DesignConfig.mu_k_ratio": ("–", "or μk = ratio·μs; omitted: the [pedestal]'s ratio"),
    "DesignConfig.pedestal_mass": ("kg", "pedestal masses to sweep too (each > 0); omitted: the [pedestal]'s"),
    "DesignConfig.sliding_limit": ("m", "the free space around the pedestal"),
    "DesignConfig.residual_limit": ("m", "largest acceptable residual sliding"),
    "DesignConfig.top_friction_limit": ("–", "friction the statue–pedestal face can supply; omitted: the "
                                             "statue's μs"),
    "DesignConfig.objective": ("", "statistic of the peak θ/α over the motions that is minimised"),
    "DesignConfig.friction_scatter": ("–", "relative scatter s: safe only if the statue survives at μs·(1 ± s)"),
    "DesignConfig.free_time": ("s", "longest free motion after each motion"),
    "DesignConfig.mu_s_top": ("–", "candidate static friction of the statue–pedestal face (each ≥ 0); given: both "
                                   "faces are designed on the stack engine"),
    "DesignConfig.mu_k_top": ("–", "a fixed kinetic friction of that face (capped at each μs)"),
    "DesignConfig.mu_k_top_ratio": ("–", "or its μk = ratio·μs; omitted: the given top face's ratio"),
    "DesignConfig.pedestal_width": ("m", "pedestal widths to sweep (each > 0); given: the stack engine, as for "
                                         "mu_s_top"),
    "DesignConfig.top_sliding_limit": ("m", "largest peak slide of the statue on the pedestal's top face (> 0, or "
                                            "inf: none); omitted, on the stack engine: half the room there, "
                                            "0.5·((pedestal width − statue width)/2 − |offset|) per width"),
    "_StackStudy.blocks": ("", "the blocks from the floor up, as in stack files; the design's pedestal is the "
                               "first, its statue the second"),
    "_StackStudy.interfaces": ("", "the contacts from the floor up, as in stack files; the design's floor face is "
                                   "the first, its top face the second"),
    "_StackStudy.simulation": ("", "as in study files (not duration nor free_time_limit)"),
    "DesignStackStudy.motions": ("", "as in design files"),
    "DesignStackStudy.design": ("", "as in design files; mu_s sweeps the floor face, mu_s_top the top face, "
                                    "pedestal_mass and pedestal_width the first block"),
    # [fragility]
    "FragilityConfig.records": ("", "the record set"),
    "FragilityConfig.pga_levels": ("m/s²", "PGA ladder"),
    "FragilityConfig.pgv_levels": ("m/s", "PGV ladder"),
    "FragilityConfig.compare_alone": ("", "also run the statue alone on the floor"),
    "FragilityConfig.alone_friction": ("–", "friction of the statue alone on the floor; omitted: the statue's"),
    "FragilityConfig.band": ("", "confidence band of the fitted curve"),
    "FragilityConfig.bootstrap": ("–", "bootstrap samples"),
    "FragilityConfig.confidence": ("–", "confidence level of the band"),
    "FragilityConfig.seed": ("–", "random seed of the bootstrap"),
    "FragilityConfig.free_time": ("s", "longest free motion after each record"),
    # [spectrum]
    "SpectrumConfig.motions": ("", "pulse shapes and/or harmonic motion"),
    "SpectrumConfig.frequency_ratio": ("–", "β = ω_p/p"),
    "SpectrumConfig.amplitude_ratio": ("–", "scanned range of a_p/(g tan α)"),
    "SpectrumConfig.n_scan": ("–", "points of the coarse amplitude scan"),
    "SpectrumConfig.rtol": ("–", "relative width to which each boundary is bisected"),
    "SpectrumConfig.criterion": ("", "what counts as failure"),
    "SpectrumConfig.phase": ("rad", "sine-pulse phase ψ, or \"onset\" = asin(1/A)"),
    "SpectrumConfig.cycles": ("–", "cycles of the harmonic motion"),
    "SpectrumConfig.free_time": ("1/p", "longest free motion after the motion"),
    "SpectrumConfig.undetermined": ("", "how a run still moving at that cap (with energy enough to fall) or stopped "
                                        "by the solver counts: \"fail\" (conservative) or \"safe\""),
}

#: (heading, the model of the whole file, a sentence) for each kind of file.
TABLES: tuple[tuple[str, type[BaseModel], str], ...] = (
    ("Run files (`rocking run`, `report`, `animate`)", run_config.Config,
     "One statue, optionally on a pedestal, under one floor motion."),
    ("Stack files (`rocking run`)", run_config.StackConfig,
     "A stack of blocks from the floor up (`rocking.stack`, docs/theory/stack.md) under one floor motion, in "
     "place of `[statue]` and `[pedestal]`; `[motion]` and `[simulation]` are those of run files."),
    ("`rocking design`", studies.DesignStudy, "The pedestal's floor friction (and mass) over a set of motions. "
     "`[statue]`, `[pedestal]` and `[simulation]` are those of run files."),
    ("Stack study files (`rocking design`, `fragility`, `spectrum`)", studies.DesignStackStudy,
     "A study of a stack of blocks on the stack engine: `[[blocks]]` and `[[interfaces]]` of stack files in place of "
     "`[statue]` and `[pedestal]`, with the study's own tables (shown here for `rocking design`; a fragility or "
     "spectrum file takes `[fragility]` or `[spectrum]` instead of `[motions]` and `[design]`)."),
    ("`rocking fragility`", studies.FragilityStudy, "Fragility curves by incremental dynamic analysis, with the "
     "tables of run files."),
    ("`rocking spectrum`", studies.SpectrumStudy, "Overturning spectra of pulses and harmonic motion, with the "
     "tables of run files."),
)


def _models(annotation: Any) -> list[type[BaseModel]]:
    """The pydantic models inside an annotation (a table, an optional table, a union)."""
    if isinstance(annotation, type) and issubclass(annotation, BaseModel):
        return [annotation]
    out: list[type[BaseModel]] = []
    for arg in typing.get_args(annotation):
        for m in _models(arg):
            if m not in out:
                out.append(m)
    return out


def _type_name(annotation: Any) -> str:
    origin = typing.get_origin(annotation)
    args = typing.get_args(annotation)
    if origin is typing.Annotated:
        return _type_name(args[0])
    if origin is Literal:
        return "string" if all(isinstance(a, str) for a in args) else "literal"
    if origin in (typing.Union, types.UnionType):
        names = [_type_name(a) for a in args if a is not type(None)]
        return " or ".join(dict.fromkeys(names))
    if origin is list:
        if args and _models(args[0]):
            return "array of tables"
        return f"array of {_type_name(args[0])}" if args else "array"
    if isinstance(annotation, type) and issubclass(annotation, BaseModel):
        return "grid table" if annotation is studies.GridConfig else "table"
    return {float: "number", int: "integer", str: "string", bool: "true/false"}.get(annotation, str(annotation))


def _literals(annotation: Any) -> list[Any]:
    if typing.get_origin(annotation) is Literal:
        return list(typing.get_args(annotation))
    out: list[Any] = []
    for arg in typing.get_args(annotation):
        out += [v for v in _literals(arg) if v not in out]
    return out


def _bounds(annotation: Any, info: FieldInfo) -> list[str]:
    marks = {"gt": ">", "ge": "≥", "lt": "<", "le": "≤", "min_length": "at least", "max_length": "at most"}
    out: list[str] = []

    def visit(meta: list[Any]) -> None:
        for m in meta:
            if isinstance(m, FieldInfo):  # Field(...) inside Annotated[...] of an optional key
                visit(list(m.metadata))
                continue
            for key, sign in marks.items():
                v = getattr(m, key, None)
                if v is None:
                    continue
                if key == "min_length" and v == 1:
                    text = "not empty"
                else:
                    text = f"{sign} {_number(v)}" + (" values" if "length" in key else "")
                if text not in out:
                    out.append(text)

    visit(list(info.metadata))
    for arg in (annotation, *typing.get_args(annotation)):
        if typing.get_origin(arg) is typing.Annotated:
            visit(list(typing.get_args(arg)[1:]))
    return out


def _number(v: Any) -> str:
    if isinstance(v, float):
        if math.isclose(v, 2 * math.pi):
            return "2π"
        return f"{v:g}"
    return str(v)


def _default(info: FieldInfo) -> str:
    if info.is_required():
        return "required"
    v = info.default
    if v is PydanticUndefined or v is None:
        return "omitted"
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, str):
        return f'"{v}"'
    if isinstance(v, float):
        return _number(v)
    if isinstance(v, BaseModel):
        if isinstance(v, studies.GridConfig):
            return f"{v.num} values, {v.start:g} to {v.stop:g} ({v.spacing})"
        return "see its table"
    if isinstance(v, list):
        return "[" + ", ".join(f'"{x}"' if isinstance(x, str) else _number(x) for x in v) + "]"
    return str(v)


def _meaning(model: type[BaseModel], key: str) -> tuple[str, str]:
    """(unit, meaning) of ``key``, looked up on the model or the class it inherits the key from."""
    for cls in model.__mro__:
        found = MEANING.get(f"{cls.__name__}.{key}")
        if found is not None:
            return found
    return "?", "?"


def rows(model: type[BaseModel], prefix: str = "") -> Iterator[tuple[str, str, dict[str, str]]]:
    """(dotted table, model name, row) for ``model`` and every table inside it, depth first."""
    own: list[dict[str, str]] = []
    inner: list[tuple[str, type[BaseModel]]] = []
    for key, info in model.model_fields.items():
        annotation = info.annotation
        unit, meaning = _meaning(model, key)
        allowed = [f'"{v}"' if isinstance(v, str) else str(v) for v in _literals(annotation)]
        own.append({
            "key": key, "type": _type_name(annotation), "default": _default(info), "unit": unit or "",
            "allowed": ", ".join(allowed + _bounds(annotation, info)), "meaning": meaning,
        })
        # an array of tables is written [[key]] in TOML: its label carries one pair of brackets
        array = typing.get_origin(annotation) is list
        for sub in _models(annotation):
            inner.append((f"[{prefix}{key}]" if array else f"{prefix}{key}", sub))
    yield prefix.rstrip("."), model.__name__, own  # type: ignore[misc]
    for name, sub in inner:
        label = name
        if name.endswith("motion") and sub is not run_config.RecordConfig and hasattr(sub, "model_fields"):
            kind = sub.model_fields.get("shape") or sub.model_fields.get("kind")
            tags = _literals(kind.annotation) if kind is not None else []
            label = f"{name} ({tags[0]})" if tags else name
        elif name.endswith("motion"):
            label = f"{name} (record)"
        yield from rows(sub, f"{label}.")


def reference() -> str:
    """The whole page, as Markdown."""
    out = [
        "# Configuration reference",
        "",
        "Generated from the configuration schema by `python -m rocking.cli.config_reference --out "
        "docs/configuration.md`; a test fails when it is out of date. Units are SI; angles in radians. "
        "A key not listed is refused with its name and a suggestion. \"omitted\" means the key may be "
        "left out (its meaning then says what happens).",
        "",
    ]
    printed: set[str] = set()  # a table shared by several files (or keys) is described once
    for heading, model, sentence in TABLES:
        out += [f"## {heading}", "", sentence, ""]
        for table, name, table_rows in rows(model):
            if name in printed and name not in ("Config", "StackConfig", "DesignStudy", "FragilityStudy",
                                                "SpectrumStudy"):
                continue
            printed.add(name)
            if name == "GridConfig":
                title = (f"### a grid, e.g. `[{table}]`: every key whose type says \"grid table\" also takes "
                         "an array of numbers")
            else:
                title = f"### `[{table}]`" if table else "### top level"
            out += [title, ""]
            out += ["| key | type | default | unit | allowed | meaning |", "|---|---|---|---|---|---|"]
            for r in table_rows:
                cells = [f"`{r['key']}`", r["type"], r["default"], r["unit"], r["allowed"], r["meaning"]]
                out.append("| " + " | ".join(c.replace("|", "\\|") for c in cells) + " |")
            out.append("")
    return "\n".join(out).rstrip("\n") + "\n"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m rocking.cli.config_reference", description=__doc__.split("\n")[0])
    parser.add_argument("--out", type=Path, help="write the page here (default: print it)")
    args = parser.parse_args(argv)
    text = reference()
    if args.out is None:
        print(text, end="")
    else:
        args.out.write_text(text, encoding="utf-8")
        print(f"wrote {args.out}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
