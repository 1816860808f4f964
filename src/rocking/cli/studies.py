"""``rocking design``, ``rocking fragility`` and ``rocking spectrum``: studies of many runs.

Each command reads a TOML file with the ``[statue]``, optional ``[pedestal]`` and optional
``[simulation]`` tables of ``rocking run`` (see :mod:`rocking.io.config`) plus the study's own
tables (described in :func:`load_study` and ``docs/studies.md``), runs the study on local
processes (``--workers``) or on a Dask cluster (``--scheduler``), saves every finished chunk
of runs in ``OUT/chunks*`` (so the same command, rerun after an interruption, resumes where it
stopped) and writes tables, NetCDF data sets, charts and a Markdown report into ``OUT``.

``register(app)`` adds the commands to the typer application of :mod:`rocking.cli.main`.
"""

from __future__ import annotations

import contextlib
import difflib
import math
import os
from collections.abc import Iterator, Mapping
from pathlib import Path
from typing import Annotated, Any, Literal, Optional

import numpy as np
import typer
from pydantic import BaseModel, Field, PrivateAttr, ValidationError, field_validator, model_validator

from ..io.config import (
    BlockConfig,
    ConfigError,
    FrictionConfig,
    InterfaceConfig,
    NonNegative,
    PedestalConfig,
    Positive,
    SimulationConfig,
    StatueConfig,
    _describe,
    _field,
    _read_toml,
    _Section,
)

__all__ = [
    "DesignStackStudy",
    "DesignStudy",
    "FragilityStackStudy",
    "FragilityStudy",
    "SpectrumStudy",
    "design",
    "fragility",
    "load_study",
    "register",
    "spectrum",
    "SpectrumStackStudy",
]


# ===================================================================== configuration models
class GridConfig(_Section):
    """``{ start = .., stop = .., num = .., spacing = "linear" | "log" }`` (both ends included)."""

    start: float
    stop: float
    num: Annotated[int, Field(ge=1, le=100_000)]
    spacing: Literal["linear", "log"] = "linear"

    @model_validator(mode="after")
    def _order(self) -> GridConfig:
        if self.spacing == "log" and not (self.start > 0 and self.stop > 0):
            raise ValueError("a log grid needs start > 0 and stop > 0")
        return self

    def values(self) -> list[float]:
        if self.spacing == "log":
            return np.geomspace(self.start, self.stop, self.num).tolist()
        return np.linspace(self.start, self.stop, self.num).tolist()


Grid = list[float] | GridConfig


def _grid(value: Grid) -> list[float]:
    return value.values() if isinstance(value, GridConfig) else [float(v) for v in value]


def _checked_grid(value: Grid, ok: Any, bound: str) -> Grid:
    """``value`` if it holds at least one value and every value satisfies ``ok``; else a
    ValueError that the config error reports under the grid's own dotted field."""
    values = _grid(value)
    if not values:
        raise ValueError("must hold at least one value")
    bad = next((x for x in values if not ok(x)), None)
    if bad is not None:
        where = " (a value of the grid)" if isinstance(value, GridConfig) else ""
        raise ValueError(f"every value must be {bound}, got {bad:g}{where}")
    return value


class MotionSetConfig(_Section):
    """``[motions]``: records scaled to one intensity, or a harmonic/pulse family."""

    records: list[Annotated[str, Field(min_length=1)]] | None = None
    pga: Positive | None = None  # m/s²
    pgv: Positive | None = None  # m/s
    scale: Positive | None = None
    family: Literal["harmonic", "sine", "cosine", "ricker"] | None = None
    amplitude: Grid | None = None  # m/s²
    frequency: Grid | None = None  # Hz
    cycles: Positive = 3.0
    form: Literal["cos", "sin"] = "sin"

    @model_validator(mode="after")
    def _one_kind(self) -> MotionSetConfig:
        if (self.records is None) == (self.family is None):
            raise ValueError("give either records = [...] or family = \"harmonic\" | \"sine\" | \"cosine\" | \"ricker\"")
        if self.records is not None:
            if not self.records:
                raise ValueError("records must not be empty")
            if sum(v is not None for v in (self.pga, self.pgv, self.scale)) > 1:
                raise ValueError("give at most one of pga, pgv and scale")
            if self.amplitude is not None or self.frequency is not None:
                raise ValueError("amplitude and frequency belong to a family, not to records")
        else:
            if self.amplitude is None or self.frequency is None:
                raise ValueError("a family needs amplitude and frequency (numbers or grids)")
            if any(v is not None for v in (self.pga, self.pgv, self.scale)):
                raise ValueError("pga, pgv and scale apply to records; give a family's amplitude instead")
        return self


class DesignConfig(_Section):
    """``[design]``: the friction (and mass) sweep and the limits."""

    mu_s: Grid
    mu_k: NonNegative | None = None
    mu_k_ratio: Annotated[float, Field(ge=0, le=1)] | None = None
    pedestal_mass: Grid | None = None
    sliding_limit: NonNegative | None = None  # m
    residual_limit: NonNegative | None = None  # m
    top_friction_limit: NonNegative | None = None
    objective: Literal["mean", "median", "max"] = "mean"
    friction_scatter: Annotated[float, Field(ge=0, lt=1)] = 0.2  # relative: candidates also run at μs·(1 ± s)
    free_time: NonNegative = 60.0  # s: longest free motion after each record (runs end at rest)
    # the top face and the width: any of them runs the study on the stack engine
    mu_s_top: Grid | None = None
    mu_k_top: NonNegative | None = None
    mu_k_top_ratio: Annotated[float, Field(ge=0, le=1)] | None = None
    pedestal_width: Grid | None = None  # m
    # m: the statue's slide on the top face; inf (which TOML writes as a literal) for no limit
    top_sliding_limit: Annotated[float, Field(allow_inf_nan=True)] | None = None

    @field_validator("mu_s", "mu_s_top")
    @classmethod
    def _friction_values(cls, v: Grid | None) -> Grid | None:
        # checked here, not by friction_design, so that the message names design.mu_s and the file
        return None if v is None else _checked_grid(v, lambda x: x >= 0, ">= 0")

    @field_validator("pedestal_mass", "pedestal_width")
    @classmethod
    def _mass_values(cls, v: Grid | None) -> Grid | None:
        # > 0 as [pedestal] mass: a massless pedestal is the statue sliding on the floor
        return None if v is None else _checked_grid(v, lambda x: x > 0, "> 0")

    @field_validator("top_sliding_limit")
    @classmethod
    def _room_on_top(cls, v: float | None) -> float | None:
        # NaN passes a pydantic bound, and 0 would forbid any slip: refused here, with the field's name
        if v is not None and not v > 0:
            raise ValueError(f"must be a number > 0 (m), or inf for no limit, got {v!r}")
        return v

    @model_validator(mode="after")
    def _one_kinetic(self) -> DesignConfig:
        if self.mu_k is not None and self.mu_k_ratio is not None:
            raise ValueError("give mu_k or mu_k_ratio, not both")
        if self.mu_k_top is not None and self.mu_k_top_ratio is not None:
            raise ValueError("give mu_k_top or mu_k_top_ratio, not both")
        if self.mu_s_top is None and (self.mu_k_top is not None or self.mu_k_top_ratio is not None):
            raise ValueError("mu_k_top and mu_k_top_ratio go with mu_s_top (the statue–pedestal face's μs)")
        return self

    @property
    def two_faces(self) -> bool:
        """A top-face or width axis: the study runs on the stack engine."""
        return self.mu_s_top is not None or self.pedestal_width is not None


class FragilityConfig(_Section):
    """``[fragility]``: the record set, the intensity ladders and the fit."""

    records: list[Annotated[str, Field(min_length=1)]]
    pga_levels: Grid | None = None  # m/s²
    pgv_levels: Grid | None = None  # m/s
    compare_alone: bool = True
    alone_friction: FrictionConfig | None = None
    band: Literal["bootstrap", "fisher", "none"] = "bootstrap"
    bootstrap: Annotated[int, Field(ge=10, le=100_000)] = 400
    confidence: Annotated[float, Field(gt=0, lt=1)] = 0.9
    seed: int = 0
    free_time: NonNegative = 60.0  # s: longest free motion after each record (runs end at rest)

    @model_validator(mode="after")
    def _some_levels(self) -> FragilityConfig:
        if self.pga_levels is None and self.pgv_levels is None:
            raise ValueError("give pga_levels (m/s²) and/or pgv_levels (m/s)")
        if not self.records:
            raise ValueError("records must not be empty")
        return self


class SpectrumConfig(_Section):
    """``[spectrum]``: motions, β grid, amplitude range, criterion, tolerances."""

    motions: list[Literal["sine", "cosine", "ricker", "harmonic"]] = ["sine", "cosine"]
    frequency_ratio: Grid = GridConfig(start=0.5, stop=8.0, num=25, spacing="log")
    amplitude_ratio: Annotated[list[Positive], Field(min_length=2, max_length=2)] = [1.01, 30.0]
    n_scan: Annotated[int, Field(ge=2, le=10_000)] = 48
    rtol: Annotated[float, Field(gt=0, lt=1)] = 1e-3
    criterion: Literal["overturn", "no_impact", "exceed"] = "overturn"
    phase: Literal["onset"] | Annotated[float, Field(ge=0, lt=2 * math.pi)] = "onset"
    cycles: Positive = 3.0
    free_time: NonNegative = 25.0  # units of 1/p
    undetermined: Literal["fail", "safe"] = "fail"  # how a run without an outcome counts


class _Study(_Section):
    statue: StatueConfig
    pedestal: PedestalConfig | None = None
    simulation: SimulationConfig = SimulationConfig()

    _source: str | None = PrivateAttr(default=None)


class DesignStudy(_Study):
    """A ``rocking design`` file: [statue], [pedestal], [motions], [design], [simulation]."""

    motions: MotionSetConfig
    design: DesignConfig


class FragilityStudy(_Study):
    """A ``rocking fragility`` file: [statue], optional [pedestal], [fragility], [simulation]."""

    fragility: FragilityConfig


class SpectrumStudy(_Study):
    """A ``rocking spectrum`` file: [statue], optional [pedestal], [spectrum], [simulation]."""

    spectrum: SpectrumConfig = SpectrumConfig()


class _StackStudy(_Section):
    blocks: Annotated[list[BlockConfig], Field(min_length=1)]
    interfaces: list[InterfaceConfig]
    simulation: SimulationConfig = SimulationConfig()

    _source: str | None = PrivateAttr(default=None)


class DesignStackStudy(_StackStudy):
    """A ``rocking design`` file of a stack: [[blocks]] (the pedestal first, on the floor),
    [[interfaces]] (the floor face first, then the top face), [motions], [design], [simulation]."""

    motions: MotionSetConfig
    design: DesignConfig


class FragilityStackStudy(_StackStudy):
    """A ``rocking fragility`` file of a stack: [[blocks]], [[interfaces]], [fragility], [simulation]."""

    fragility: FragilityConfig


class SpectrumStackStudy(_StackStudy):
    """A ``rocking spectrum`` file of a stack: [[blocks]], [[interfaces]], [spectrum], [simulation]."""

    spectrum: SpectrumConfig = SpectrumConfig()


_STUDIES: dict[str, type[_Study]] = {"design": DesignStudy, "fragility": FragilityStudy, "spectrum": SpectrumStudy}
_STACK_STUDIES: dict[str, type[_StackStudy]] = {"design": DesignStackStudy, "fragility": FragilityStackStudy,
                                                "spectrum": SpectrumStackStudy}


def _known_keys(model: type[BaseModel], loc: tuple[Any, ...]) -> list[str]:
    """Keys of the table at ``loc`` (for 'did you mean')."""
    for key in loc:
        field = model.model_fields.get(key) if isinstance(key, str) else None
        if field is None:
            return []
        nested = [a for a in _flatten(field.annotation) if isinstance(a, type) and issubclass(a, BaseModel)]
        if not nested:
            return []
        model = nested[0]
    return list(model.model_fields)


def _flatten(annotation: Any) -> Iterator[Any]:
    args = getattr(annotation, "__args__", None)
    if args:
        for a in args:
            yield from _flatten(a)
    else:
        yield annotation


def _problems(model: type[BaseModel], errors: list[Mapping[str, Any]]) -> list[tuple[str | None, str]]:
    """Plain-words problems from pydantic errors, without the noise of the unions (a grid is a
    list or a table: only the branch that matches what the user wrote is reported)."""
    cleaned = []
    for err in errors:
        # union members appear in the location as "list[float]", "function-after[..., GridConfig]"
        loc = tuple(p for p in err["loc"] if not (isinstance(p, str) and "[" in p))
        cleaned.append({**err, "loc": loc})
    by_field: dict[tuple[Any, ...], int] = {}
    for err in cleaned:
        by_field[err["loc"][:2]] = by_field.get(err["loc"][:2], 0) + 1
    out = []
    for err, raw in zip(cleaned, errors):
        branch_mismatch = (
            (err["type"] == "list_type" and isinstance(err.get("input"), Mapping))
            or (err["type"] in ("model_type", "dict_type") and isinstance(err.get("input"), list))
        )
        if branch_mismatch and by_field.get(err["loc"][:2], 0) > 1:
            continue
        field, message = _describe(err)
        if err["type"] == "extra_forbidden":
            known = _known_keys(model, err["loc"][:-1])
            close = difflib.get_close_matches(str(err["loc"][-1]), known, n=1, cutoff=0.6)
            message = f"unknown key; did you mean {close[0]!r}?" if close else (
                f"unknown key; known keys: {', '.join(known)}" if known else "unknown key")
        elif err["type"] in ("list_type", "model_type", "dict_type") and len(raw["loc"]) > len(err["loc"]):
            message = "must be a list of numbers or a table { start, stop, num }"
        if (field, message) not in out:
            out.append((field, message))
    return out


def _study_model(kind: str, data: Any, source: str | None) -> type[_Study] | type[_StackStudy]:
    """The stack variant of a study for a file with [[blocks]] or [[interfaces]]; mixing them with
    [statue] or [pedestal] is refused, naming the table."""
    stack = [k for k in ("blocks", "interfaces") if isinstance(data, Mapping) and k in data]
    if not stack:
        return _STUDIES[kind]
    single = [f"[{k}]" for k in ("statue", "pedestal") if k in data]
    if single:
        raise ConfigError([(stack[0], f"[[{stack[0]}]] describes a stack, which cannot also have "
                            f"{' or '.join(single)}: give either [statue] (and [pedestal]) or [[blocks]] and "
                            "[[interfaces]]")], source)
    return _STACK_STUDIES[kind]


def load_study(kind: str, config: str | os.PathLike[str] | Mapping[str, Any]) -> tuple[_Study, Path]:
    """Read and validate a study file.

    Parameters
    ----------
    kind : {"design", "fragility", "spectrum"}
    config : path-like or mapping

    Returns
    -------
    (model, base_dir)
        The validated model (a stack study for a file with ``[[blocks]]``) and the folder
        against which relative record paths resolve.

    Raises
    ------
    ConfigError
        Naming the file and the dotted field.
    """
    if isinstance(config, Mapping):
        source, data, base = None, config, Path.cwd()
    else:
        source = os.fspath(config)
        data = _read_toml(Path(config), source)
        base = Path(config).resolve().parent
    model = _study_model(kind, data, source)
    try:
        study = model.model_validate(data)
    except ValidationError as exc:
        raise ConfigError(_problems(model, exc.errors()), source) from None
    study._source = source
    for key in ("duration", "free_time_limit"):
        if key in study.simulation.model_fields_set:
            raise ConfigError([(f"simulation.{key}", f"not used by `rocking {kind}`: each run lasts its motion, then "
                                f"free motion until at rest, for at most {kind}.free_time")], source)
    return study, base


# ================================================================== from the models to specs
def _stack_spec(study: _StackStudy, source: str | None):
    """(stack, options) of a stack study, checked as ``rocking run`` checks a stack file."""
    from ..io.config import StackConfig
    from ..stack.model import Block, Interface, Stack

    # the run file's checks (interfaces per block, names, overlaps, normal_force) in its words
    cfg = StackConfig.model_construct(blocks=study.blocks, interfaces=study.interfaces, simulation=study.simulation)
    cfg._source = source
    cfg._check_stack()
    blocks = []
    for i, b in enumerate(study.blocks):
        with _field(f"blocks[{i}]", source):
            blocks.append(Block(width=b.width, height=b.height, mass=b.mass, inertia=b.inertia, offset=b.offset,
                                name=b.name or ""))
    interfaces = []
    for i, f in enumerate(study.interfaces):
        with _field(f"interfaces[{i}]", source):
            interfaces.append(Interface(friction=f.friction.to_spec() if f.friction else None,
                                        restitution=f.restitution))
    with _field(None, source):
        stack = Stack(blocks=tuple(blocks), interfaces=tuple(interfaces))
    return stack, _options(study, source)


def _options(study: Any, source: str | None):
    from ..simulation import Options

    sim = study.simulation
    with _field("simulation", source):
        return Options(gravity=sim.gravity, normal_force=sim.normal_force, impact=sim.impact, rtol=sim.rtol,
                       atol=sim.atol, max_step=sim.max_step, rest_velocity=sim.rest_velocity, save_dt=sim.save_dt,
                       max_events=sim.max_events)


def _specs(study: _Study, source: str | None):
    from ..contact.friction import Friction
    from ..models.bodies import Pedestal, Statue, System
    from ..simulation import Options

    with _field("statue", source):
        s = study.statue
        statue = Statue(width=s.width, height=s.height, mass=s.mass, restitution=s.restitution,
                        friction=s.friction.to_spec() if s.friction else None)
    pedestal = None
    if study.pedestal is not None:
        with _field("pedestal", source):
            p = study.pedestal
            pedestal = Pedestal(mass=p.mass, friction=Friction(static=p.friction.static, kinetic=p.friction.kinetic),
                                width=p.width, height=p.height)
    sim = study.simulation
    with _field("simulation", source):
        options = Options(gravity=sim.gravity, normal_force=sim.normal_force, impact=sim.impact, rtol=sim.rtol,
                          atol=sim.atol, max_step=sim.max_step, rest_velocity=sim.rest_velocity, save_dt=sim.save_dt,
                          max_events=sim.max_events)
    with _field(None, source):
        system = System(statue=statue, pedestal=pedestal)
    return statue, pedestal, system, options


def _records(items: list[str], base: Path, source: str | None, field: str) -> dict[str, Any]:
    from ..analyses.fragility import load_record_set
    from ..io.records import RecordError

    try:
        return load_record_set(items, base_dir=base)
    except (RecordError, FileNotFoundError) as exc:
        raise ConfigError([(field, " ".join(str(exc).split()))], source) from None


def design_inputs(study: DesignStudy, base: Path) -> dict[str, Any]:
    """Keyword arguments of :func:`rocking.analyses.design.friction_design` from a design file."""
    from ..analyses.design import motion_family

    src = getattr(study, "_source", None)
    d = study.design
    if isinstance(study, _StackStudy):
        system, options = _stack_spec(study, src)
        if system.n < 2:
            raise ConfigError([("blocks", "the design needs a pedestal (the first [[blocks]], on the floor) and what "
                                "stands on it: at least two blocks")], src)
        if system.interfaces[0].friction is None:
            raise ConfigError([("interfaces[0].friction", "missing (required): the floor face's friction is what the "
                                "design sweeps")], src)
    else:
        statue, pedestal, system, options = _specs(study, src)
        if pedestal is None:
            raise ConfigError([("pedestal", "missing (required): the design sweeps the pedestal's friction")], src)
        if d.top_sliding_limit is not None and not d.two_faces:
            raise ConfigError([("design.top_sliding_limit", "applies on the stack engine, where the statue may slip "
                                "on the pedestal: give design.mu_s_top or design.pedestal_width too, or describe "
                                "the stack with [[blocks]]")], src)
        if d.two_faces:
            axis = "design.mu_s_top" if d.mu_s_top is not None else "design.pedestal_width"
            if pedestal.height is None:
                raise ConfigError([("pedestal.height", f"missing: {axis} runs the stack engine, where the pedestal "
                                    "may rock, so it needs its height (m)")], src)
            if pedestal.width is None and d.pedestal_width is None:
                raise ConfigError([("pedestal.width", f"missing: {axis} runs the stack engine, where the pedestal "
                                    "may rock, so it needs its width (m), or give design.pedestal_width")], src)
    m = study.motions
    if m.records is not None:
        recs = _records(m.records, base, src, "motions.records")
        motions = {}
        with _field("motions", src):
            for name, rec in recs.items():
                if m.pga is not None:
                    motions[name] = rec.scaled(pga=m.pga)
                elif m.pgv is not None:
                    motions[name] = rec.scaled(m.pgv / rec.pgv)
                elif m.scale is not None:
                    motions[name] = rec.scaled(m.scale)
                else:
                    motions[name] = rec
    else:
        with _field("motions", src):
            motions = motion_family(m.family, _grid(m.amplitude), _grid(m.frequency), cycles=m.cycles, form=m.form)
    out = dict(system=system, motions=motions, mu_s=_grid(d.mu_s), mu_k=d.mu_k, mu_k_ratio=d.mu_k_ratio,
               pedestal_mass=_grid(d.pedestal_mass) if d.pedestal_mass is not None else None,
               sliding_limit=d.sliding_limit, residual_limit=d.residual_limit,
               top_friction_limit=d.top_friction_limit, objective=d.objective,
               friction_scatter=d.friction_scatter, free_time=d.free_time, options=options)
    if d.two_faces or isinstance(study, _StackStudy):
        out.update(mu_s_top=_grid(d.mu_s_top) if d.mu_s_top is not None else None, mu_k_top=d.mu_k_top,
                   mu_k_top_ratio=d.mu_k_top_ratio, top_sliding_limit=d.top_sliding_limit,
                   pedestal_width=_grid(d.pedestal_width) if d.pedestal_width is not None else None)
    return out


def fragility_inputs(study: FragilityStudy, base: Path) -> dict[str, Any]:
    """``systems``, ``records``, ``levels`` (per IM) and the fit settings of a fragility file."""
    from ..models.bodies import System

    src = getattr(study, "_source", None)
    f = study.fragility
    if isinstance(study, _StackStudy):
        stack, options = _stack_spec(study, src)
        systems = {}
        if f.compare_alone:
            systems["statue alone"] = _alone_block(stack, f.alone_friction)
        systems["stack"] = stack
        recs = _records(f.records, base, src, "fragility.records")
        return dict(systems=systems, records=recs, levels=_levels(f, src), options=options, free_time=f.free_time,
                    band=f.band, n_boot=f.bootstrap, confidence=f.confidence, seed=f.seed)
    statue, pedestal, system, options = _specs(study, src)
    if pedestal is None:
        alone = statue
        if f.alone_friction is not None:
            alone = _replace_friction(statue, f.alone_friction)
        systems = {"statue alone": System(statue=alone)}
    else:
        systems = {}
        if f.compare_alone:
            alone = _replace_friction(statue, f.alone_friction)  # statue.friction is the top face here
            systems["statue alone"] = System(statue=alone)
        systems["on pedestal"] = system
    recs = _records(f.records, base, src, "fragility.records")
    return dict(systems=systems, records=recs, levels=_levels(f, src), options=options, free_time=f.free_time,
                band=f.band, n_boot=f.bootstrap, confidence=f.confidence, seed=f.seed)


def _levels(f: FragilityConfig, src: str | None) -> dict[str, list[float]]:
    levels = {}
    if f.pga_levels is not None:
        levels["pga"] = _positive_grid(f.pga_levels, "fragility.pga_levels", src)
    if f.pgv_levels is not None:
        levels["pgv"] = _positive_grid(f.pgv_levels, "fragility.pgv_levels", src)
    return levels


def _alone_block(stack: Any, friction: FrictionConfig | None) -> Any:
    """The stack's top block standing alone on the floor (a one-block stack), with
    ``alone_friction`` on the floor (omitted: it never slips) and its interface's restitution."""
    import dataclasses

    from ..stack.model import Stack

    face = dataclasses.replace(stack.interfaces[-1], friction=friction.to_spec() if friction is not None else None)
    return Stack(blocks=(dataclasses.replace(stack.blocks[-1], offset=0.0),), interfaces=(face,))


def _replace_friction(statue: Any, friction: FrictionConfig | None) -> Any:
    import dataclasses

    return dataclasses.replace(statue, friction=friction.to_spec() if friction is not None else None)


def _positive_grid(grid: Grid, field: str, src: str | None) -> list[float]:
    values = _grid(grid)
    if not values or any(not (v > 0 and math.isfinite(v)) for v in values):
        raise ConfigError([(field, f"levels must be positive numbers, got {values!r}")], src)
    return values


def spectrum_inputs(study: SpectrumStudy, base: Path) -> dict[str, Any]:
    """Keyword arguments of :func:`rocking.analyses.spectra.overturning_spectrum`."""
    src = getattr(study, "_source", None)
    if isinstance(study, _StackStudy):
        system, options = _stack_spec(study, src)
    else:
        statue, pedestal, system, options = _specs(study, src)
    s = study.spectrum
    betas = _positive_grid(s.frequency_ratio, "spectrum.frequency_ratio", src)
    lo, hi = s.amplitude_ratio
    if not lo < hi:
        raise ConfigError([("spectrum.amplitude_ratio", f"must be [low, high] with low < high, got {[lo, hi]!r}")], src)
    if len(set(s.motions)) != len(s.motions) or not s.motions:
        raise ConfigError([("spectrum.motions", "must be a non-empty list without repeats")], src)
    return dict(system=system, shapes=list(s.motions), frequency_ratios=betas, amplitude_range=(lo, hi),
                n_scan=s.n_scan, rtol=s.rtol, criterion=s.criterion, phase=s.phase, cycles=s.cycles,
                free_time=s.free_time, undetermined=s.undetermined, options=options)


# ====================================================================== execution helpers
@contextlib.contextmanager
def _executor(workers: int | None, scheduler: str | None) -> Iterator[Any]:
    """``workers`` for the analyses: local processes, or a DaskExecutor on ``scheduler``
    ("local" or "local:N" starts a LocalCluster here)."""
    if scheduler is None:
        yield workers
        return
    try:
        from distributed import Client, LocalCluster
    except ImportError:
        # Dask is an optional extra: the local process pool needs none of it
        raise typer.BadParameter("needs Dask, an optional extra: pip install 'rocking[dask]'",
                                 param_hint="--scheduler") from None
    from ..analyses.executors import DaskExecutor, default_workers

    cluster = None
    if scheduler == "local" or scheduler.startswith("local:"):
        n = int(scheduler.partition(":")[2] or (workers or default_workers()))
        cluster = LocalCluster(n_workers=n, threads_per_worker=1, dashboard_address=None)
        client = Client(cluster)
    else:
        try:
            client = Client(scheduler, timeout="10s")
        except (OSError, TimeoutError) as exc:
            raise typer.BadParameter(f"cannot reach the Dask scheduler at {scheduler}: {exc}",
                                     param_hint="--scheduler") from None
    try:
        yield DaskExecutor(client)
    finally:
        client.close()
        if cluster is not None:
            cluster.close()


@contextlib.contextmanager
def _progress(description: str) -> Iterator[Any]:
    """A rich progress bar on stderr (done/total, elapsed, ETA); nothing when not a terminal."""
    from rich.console import Console
    from rich.progress import (
        BarColumn,
        MofNCompleteColumn,
        Progress,
        TextColumn,
        TimeElapsedColumn,
        TimeRemainingColumn,
    )

    console = Console(stderr=True)
    with Progress(
        TextColumn("{task.description}"),
        BarColumn(),
        MofNCompleteColumn(),
        TextColumn("runs"),
        TimeElapsedColumn(),
        TextColumn("ETA"),
        TimeRemainingColumn(),
        console=console,
        disable=not console.is_terminal,
    ) as bar:
        task = bar.add_task(description, total=None)
        first = [True]

        def update(done: int, total: int) -> None:
            if first[0]:
                # the resumed part is not work done now: start the ETA from here
                bar.reset(task, total=total, completed=done)
                first[0] = False
            else:
                bar.update(task, completed=done, total=total)

        yield update


def _out_dir(out: Path | None, config: Path, kind: str) -> Path:
    out = Path(out) if out is not None else Path(f"{config.stem}-{kind}")
    if out.exists() and not out.is_dir():
        raise typer.BadParameter(f"{out} exists and is not a directory", param_hint="--out")
    return out  # created with its chunk folder, once the workers are ready


def _replace(path: Path, tmp: Path, write: Any) -> None:
    """``write(tmp)``, then rename ``tmp`` to ``path``; on any failure or interrupt (Ctrl-C,
    SIGTERM) remove ``tmp``, so that neither a half-written file nor a temporary one stays."""
    try:
        write(tmp)
        os.replace(tmp, path)
    except BaseException:
        tmp.unlink(missing_ok=True)
        raise


def _write_text(path: Path, text: str) -> None:
    _replace(path, path.with_name(f".{path.name}.tmp"), lambda tmp: tmp.write_text(text, encoding="utf-8"))


def _write_netcdf(ds: Any, path: Path) -> None:
    _replace(path, path.with_name(f".{path.name}.tmp"), lambda tmp: ds.to_netcdf(tmp, engine="h5netcdf"))


def _write_figure(fig: Any, path: Path) -> None:
    _replace(path, path.with_name(f".{path.name}.tmp.png"), lambda tmp: fig.savefig(tmp, dpi=130))


def _warm_up() -> None:
    """Compile the solver here, once, with a message, if the cache is cold: the workers then
    load it from disk instead of each compiling it in silence."""
    from ..solver.warmup import ensure_compiled

    ensure_compiled()


@contextlib.contextmanager
def _whole_study(runs_per_part: Mapping[str, int], part: str) -> Iterator[None]:
    """Turn the interrupt of one part of a study (one intensity measure of a fragility study) into
    the count of the whole study: the parts before ``part`` are saved, the later ones not begun."""
    from ..analyses.store import StudyInterrupted

    try:
        yield
    except StudyInterrupted as exc:
        names = list(runs_per_part)
        before = sum(runs_per_part[k] for k in names[: names.index(part)])
        raise StudyInterrupted(before + exc.saved, sum(runs_per_part.values()), exc.folder,
                               signum=exc.signum) from exc


def _check_workers(workers: int | None) -> None:
    if workers is not None and workers < 1:
        raise typer.BadParameter("must be >= 1", param_hint="--workers")


_OUT = Annotated[Optional[Path], typer.Option("--out", "-o", help="Output folder (default: CONFIG's stem + '-<study>').",  # noqa: UP045
                                              show_default=False)]
_WORKERS = Annotated[Optional[int], typer.Option("--workers", "-w", help="Local processes (default: all cores).",  # noqa: UP045
                                                 show_default=False)]
_SCHEDULER = Annotated[Optional[str], typer.Option(  # noqa: UP045
    "--scheduler", help="Run on Dask: a scheduler address (tcp://host:8786), or 'local[:N]' for a LocalCluster.",
    show_default=False)]
_FRESH = Annotated[bool, typer.Option("--fresh", help="Discard the saved chunks of an earlier run in OUT.")]
_CONFIG = Annotated[Path, typer.Argument(metavar="CONFIG", help="TOML study file.", show_default=False)]


# ============================================================================== commands
def design(config: _CONFIG, out: _OUT = None, workers: _WORKERS = None, scheduler: _SCHEDULER = None,
           fresh: _FRESH = False) -> None:
    """Friction design of the pedestal: sweep its floor friction (and mass), recommend one.

    With design.mu_s_top or design.pedestal_width (or a [[blocks]] file) both faces are designed
    on the stack engine: the statue may slip on the pedestal, the pedestal may rock, and the
    report says which face does the work.

    Runs every candidate under every record or motion of the family, writes design_table.csv,
    design.nc, design_chart.png and design_report.md into OUT and prints the report. Rerun the
    same command to resume an interrupted study.
    """
    from ..analyses.design import candidate_table, design_report, friction_design, plot_design

    _check_workers(workers)
    study, base = load_study("design", config)
    inputs = design_inputs(study, base)  # type: ignore[arg-type]
    out = _out_dir(out, config, "design")
    _warm_up()
    with _executor(workers, scheduler) as ex, _progress("design") as progress:
        ds = friction_design(**inputs, workers=ex, folder=out / "chunks", fresh=fresh, progress=progress)
    _replace(out / "design_table.csv", out / ".design_table.csv.tmp",
             lambda tmp: candidate_table(ds).to_csv(tmp, index=False))
    _write_netcdf(ds, out / "design.nc")
    _write_figure(plot_design(ds), out / "design_chart.png")
    report = design_report(ds, title=f"Friction design: {config.name}")
    _write_text(out / "design_report.md", report)
    typer.echo(report, nl=False)
    typer.echo(f"wrote {out}/design_table.csv, design.nc, design_chart.png and design_report.md", err=True)


def fragility(config: _CONFIG, out: _OUT = None, workers: _WORKERS = None, scheduler: _SCHEDULER = None,
              fresh: _FRESH = False) -> None:
    """Fragility curves by incremental dynamic analysis over a record set.

    Scales every record to every PGA (and PGV) level, counts θ/α ≥ 1 and falls for the statue
    alone and on its pedestal, fits lognormal curves with confidence bands, writes
    ida_<im>.nc, fragility_<im>.nc/.csv, fragility_<im>_<mode>.png and fragility_report.md into
    OUT and prints the fits. Rerun the same command to resume an interrupted study.
    """
    from ..analyses.fragility import fragility_curves, fragility_report_lines, ida, plot_fragility_curves

    _check_workers(workers)
    study, base = load_study("fragility", config)
    inputs = fragility_inputs(study, base)  # type: ignore[arg-type]
    out = _out_dir(out, config, "fragility")
    _warm_up()
    lines = [f"# Fragility: {config.name}", "",
             f"{len(inputs['records'])} records; systems: {', '.join(inputs['systems'])}; "
             f"band: {inputs['band']} ({int(100 * inputs['confidence'])}%).", ""]
    written = []
    # runs of each intensity measure: an interrupt reports the saved runs of the whole study
    per_im = {im: len(inputs["systems"]) * len(inputs["records"]) * len(levels)
              for im, levels in inputs["levels"].items()}
    with _executor(workers, scheduler) as ex:
        for im, levels in inputs["levels"].items():
            with _progress(f"IDA {im.upper()}") as progress, _whole_study(per_im, im):
                runs = ida(inputs["systems"], inputs["records"], levels, im=im, free_time=inputs["free_time"],
                           options=inputs["options"], workers=ex, folder=out / f"chunks-{im}", fresh=fresh,
                           progress=progress)
            curves = fragility_curves(runs, band=inputs["band"], n_boot=inputs["n_boot"],
                                      confidence=inputs["confidence"], seed=inputs["seed"])
            _write_netcdf(runs, out / f"ida_{im}.nc")
            _write_netcdf(curves, out / f"fragility_{im}.nc")
            table = curves[["im_median", "beta", "se_ln_median", "se_beta", "im_median_lower", "im_median_upper",
                            "at_bound"]].to_dataframe().reset_index()
            _replace(out / f"fragility_{im}.csv", out / f".fragility_{im}.csv.tmp",
                     lambda tmp, table=table: table.to_csv(tmp, index=False))
            written += [f"ida_{im}.nc", f"fragility_{im}.nc", f"fragility_{im}.csv"]
            charts = []
            for mode in ("exceed", "fall"):
                ax = plot_fragility_curves(curves, mode, title=f"{config.stem}: {im.upper()}")
                name = f"fragility_{im}_{mode}.png"
                ax.figure.set_layout_engine("constrained")
                _write_figure(ax.figure, out / name)
                charts.append(name)
            written += charts
            lines += fragility_report_lines(curves, runs, free_time=inputs["free_time"], charts=charts)
    report = "\n".join(lines) + "\n"
    _write_text(out / "fragility_report.md", report)
    typer.echo(report, nl=False)
    typer.echo(f"wrote {out}/{', '.join(written)} and fragility_report.md", err=True)


def spectrum(config: _CONFIG, out: _OUT = None, workers: _WORKERS = None, scheduler: _SCHEDULER = None,
             fresh: _FRESH = False) -> None:
    """Overturning spectra: smallest overturning a_p/(g tan α) against ω_p/p.

    For one-sine, one-cosine and Ricker pulses and harmonic motion, with the safe islands above
    the boundary; writes spectrum.nc, spectrum.csv, spectrum.png and spectrum_report.md into OUT
    and prints the boundary. Rerun the same command to resume an interrupted study.
    """
    from ..analyses.spectra import block_text, counted_as, overturning_spectrum, plot_spectra, spectrum_report

    _check_workers(workers)
    study, base = load_study("spectrum", config)
    inputs = spectrum_inputs(study, base)  # type: ignore[arg-type]
    out = _out_dir(out, config, "spectrum")
    _warm_up()
    with _executor(workers, scheduler) as ex, _progress("spectrum (frequencies)") as progress:
        ds = overturning_spectrum(**inputs, workers=ex, folder=out / "chunks", fresh=fresh, progress=progress)
    _write_netcdf(ds, out / "spectrum.nc")
    rows = ["motion,frequency_ratio,amplitude_ratio,lower,upper,truncated,n_islands,islands"]
    for pulse in ds.pulse.values.tolist():
        sub = ds.sel(pulse=pulse)
        for k, beta in enumerate(ds.frequency_ratio.values):
            isl = [f"{a:.6g}-{b:.6g}" for a, b in zip(sub.island_lower.values[k], sub.island_upper.values[k])
                   if np.isfinite(a)]
            rows.append(f"{pulse},{beta:.6g},{sub.amplitude_ratio.values[k]:.6g},{sub.amplitude_ratio_lower.values[k]:.6g},"
                        f"{sub.amplitude_ratio_upper.values[k]:.6g},{bool(sub.truncated.values[k])},"
                        f"{int(sub.n_islands.values[k])},{' '.join(isl)}")
    _write_text(out / "spectrum.csv", "\n".join(rows) + "\n")
    a = ds.attrs
    fig = plot_spectra(ds, title=f"{config.stem}: {block_text(ds)}, criterion {a['criterion']}")
    _write_figure(fig, out / "spectrum.png")
    _write_text(out / "spectrum_report.md", spectrum_report(ds, title=f"Overturning spectra: {config.name}"))
    console_lines = [f"minimum overturning a_p/(g tan α) (α = {a['alpha']:.4f} rad, p = {a['p']:.4f} 1/s):",
                     "β = ω_p/p  " + "  ".join(f"{p:>10s}" for p in ds.pulse.values.tolist())]
    for k, beta in enumerate(ds.frequency_ratio.values):
        vals = "  ".join(f"{v:10.4g}" + ("*" if n else " ")
                         for v, n in zip(ds.amplitude_ratio.values[:, k], ds.n_islands.values[:, k]))
        console_lines.append(f"{beta:9.4g}  {vals}")
    console_lines.append("(* safe islands above the boundary: see spectrum.csv; nan: no overturning in the scanned "
                         f"range, up to {float(ds.scan_amplitude_ratio.max()):.3g})")
    undetermined = int(ds.undetermined_runs.sum())
    if undetermined:
        console_lines.append(f"warning: {undetermined} of {int(ds.runs.sum())} runs were still moving at the free-motion "
                             f"cap ({a['free_time']:g}/p after the motion): undetermined, {counted_as(ds)}; "
                             "raise spectrum.free_time")
    failed = int(ds.failed_runs.sum())
    if failed:
        console_lines.append(f"warning: {failed} of {int(ds.runs.sum())} runs were stopped by the solver before a "
                             f"verdict: {counted_as(ds)} (spectrum_report.md)")
    slid = int(ds.slid_off_runs.sum())
    if slid:
        console_lines.append(f"note: in {slid} of {int(ds.runs.sum())} runs a block slid to the edge of the one below, "
                             "where the stack engine stops: counted as failing (a fall risk)")
    typer.echo("\n".join(console_lines))
    typer.echo(f"wrote {out}/spectrum.nc, spectrum.csv, spectrum.png and spectrum_report.md", err=True)


def register(app: typer.Typer) -> None:
    """Add the ``design``, ``fragility`` and ``spectrum`` commands to ``app``."""
    app.command("design")(design)
    app.command("fragility")(fragility)
    app.command("spectrum")(spectrum)

