"""Run configurations: a TOML file (or a dict of the same shape) -> validated specs.

The file mirrors the API one table per object (SI units throughout)::

    [statue]                  # the block that rocks
    width = 0.3               # m, B
    height = 1.2              # m, H
    mass = 100.0              # kg
    restitution = 0.8         # optional; omitted = Housner's value
    friction = { static = 0.5, kinetic = 0.4 }   # optional; omitted = never slides

    [pedestal]                # optional
    mass = 50.0               # kg
    friction = { static = 0.2, kinetic = 0.15 }  # on the floor
    width = 0.5               # m, optional
    height = 0.8              # m, optional

    [motion]
    kind = "harmonic"         # or "record", "pulse"
    amplitude = 6.75          # m/s²
    frequency = 1.2           # Hz
    cycles = 30
    form = "cos"              # or "sin"

    [simulation]              # optional
    duration = 25.0           # s; default: the motion, then free motion until at rest
    free_time_limit = 60.0    # s; cap of that free motion
    gravity = 9.81            # m/s²; default 9.80665

``kind = "record"`` takes ``path`` (a file, relative to the config file's folder, or
the name of a bundled record), at most one of ``scale`` (factor) and ``pga`` (m/s²),
and optionally ``units`` and ``format`` (see :func:`rocking.io.records.read_record`);
``units`` that contradict the file's header are refused unless ``units_override = true``.
``kind = "pulse"`` takes ``shape`` ("sine", "cosine", "rectangle", "ricker"),
``amplitude`` (m/s²) and ``frequency`` (Hz) or, for a rectangle, ``width`` (s); a sine
pulse also takes ``phase`` (rad) and a Ricker wavelet ``center`` (s).

A stack of blocks (:mod:`rocking.stack`) replaces ``[statue]`` and ``[pedestal]`` by one
``[[blocks]]`` table per block and one ``[[interfaces]]`` table per contact, both from the floor
up; ``[motion]`` and ``[simulation]`` are as above::

    [[blocks]]                # block 1, on the floor
    name = "pedestal"
    width = 0.8               # m
    height = 0.5              # m
    mass = 300.0              # kg
    inertia = 25.0            # kg·m², optional; default m (B² + H²)/12
    offset = 0.0              # m, optional: centre relative to the centre of the block below
    [[blocks]]                # block 2, on block 1
    name = "statue"
    width = 0.3
    height = 1.2
    mass = 100.0
    [[interfaces]]            # floor–pedestal
    friction = { static = 0.3, kinetic = 0.25 }   # omitted: never slips
    [[interfaces]]            # pedestal–statue
    friction = { static = 0.5, kinetic = 0.4 }
    restitution = 0.8         # optional; omitted: the rule that gives Housner's value

:func:`load_config` gives a :class:`StackConfig` for such a file (a :class:`Config` otherwise).

Every problem raises :class:`ConfigError`, one line that names the file and the
dotted field, e.g. ``cfg.toml: statue.width: must be > 0, got -1``.
"""

from __future__ import annotations

import difflib
import math
import os
import re
import tomllib
from collections.abc import Iterator, Mapping
from contextlib import contextmanager
from pathlib import Path
from typing import Annotated, Any, Literal, Union

import numpy as np

from pydantic import (
    BaseModel,
    ConfigDict,
    Discriminator,
    Field,
    PrivateAttr,
    Tag,
    ValidationError,
    ValidationInfo,
    field_validator,
    model_validator,
)

from ..contact.friction import Friction
from ..excitation.record import GroundMotion
from ..excitation.harmonic import Harmonic
from ..excitation.pulses import CosinePulse, RectanglePulse, RickerPulse, SinePulse
from ..models.bodies import Pedestal, Statue, System
from ..simulation import Options
from ..stack.model import Block, Interface, Stack
from .records import RecordError, UnitsConflictError, bundled_records, read_record, units_to_si

__all__ = ["Config", "ConfigError", "StackConfig", "load_config", "load_config_and_specs"]

_DEFAULTS = Options()  # the API's defaults are the config's defaults: one source of truth


class ConfigError(ValueError):
    """An invalid configuration; the message names the file and the dotted field.

    Parameters
    ----------
    problems : list of (str or None, str)
        ``(field, message)`` pairs; ``field`` is dotted (``"statue.width"``) or None
        when the problem concerns the whole file.
    source : str, optional
        The config file as the user named it; None for a dict.

    Attributes
    ----------
    source : str or None
    field : str or None
        The first problem's field.
    problems : list of (str or None, str)
    """

    def __init__(self, problems: list[tuple[str | None, str]], source: str | None = None):
        self.source = source
        self.problems = list(problems)
        self.field = self.problems[0][0] if self.problems else None
        parts = [f"{f}: {m}" if f else m for f, m in self.problems]
        text = "; ".join(parts) if parts else "invalid configuration"
        # one line, whatever the nested messages contain: the CLI prints it as is (every
        # line break Python knows: \r, \v, \x1c, \u2028... as well as \n)
        text = " ".join(text.splitlines())
        super().__init__(f"{source}: {text}" if source else text)

    def __reduce__(self):
        # the default would call ConfigError(message) and lose the fields (dask workers
        # send exceptions back pickled)
        return (type(self), (self.problems, self.source))


# ------------------------------------------------------------------------------ models
Positive = Annotated[float, Field(gt=0)]
NonNegative = Annotated[float, Field(ge=0)]


class _Section(BaseModel):
    # strict: "1.2" or true are not numbers in a TOML file (ints are still accepted
    # for floats); allow_inf_nan: TOML has nan/inf literals, none is a valid input.
    model_config = ConfigDict(extra="forbid", strict=True, frozen=True, allow_inf_nan=False)


class FrictionConfig(_Section):
    """``{ static = μs, kinetic = μk }``; μk defaults to μs."""

    static: NonNegative
    kinetic: NonNegative | None = None

    @field_validator("kinetic")
    @classmethod
    def _kinetic_not_above_static(cls, v: float | None, info: ValidationInfo) -> float | None:
        static = info.data.get("static")
        if v is not None and static is not None and v > static:
            raise ValueError(f"must be <= static ({_show(static)}), got {_show(v)}")
        return v

    def to_spec(self) -> Friction:
        return Friction(static=self.static, kinetic=self.kinetic)


class StatueConfig(_Section):
    """``[statue]``: width and height (m), mass (kg), restitution, friction."""

    width: Positive
    height: Positive
    mass: Positive
    restitution: Annotated[float, Field(ge=0, le=1)] | None = None
    friction: FrictionConfig | None = None


class PedestalConfig(_Section):
    """``[pedestal]``: mass (kg), friction on the floor, optional width and height (m)."""

    # > 0 although the API accepts 0: a massless pedestal is the statue sliding on the
    # floor, which the config says with statue.friction and no [pedestal].
    mass: Positive
    friction: FrictionConfig
    width: Positive | None = None
    height: Positive | None = None


class HarmonicConfig(_Section):
    """``kind = "harmonic"``: A (m/s²), f (Hz), cycles, form, optional ω (rad/s)."""

    kind: Literal["harmonic"]
    amplitude: float
    frequency: Positive
    cycles: Positive = 1.0
    form: Literal["cos", "sin"] = "cos"
    angular_frequency: Positive | None = None


class RecordConfig(_Section):
    """``kind = "record"``: a file or bundled record, scaled by ``scale`` or to ``pga`` (m/s²)."""

    kind: Literal["record"]
    path: Annotated[str, Field(min_length=1)]
    scale: Positive | None = None
    pga: Positive | None = None
    units: str | None = None
    format: str | None = None
    vertical_path: Annotated[str, Field(min_length=1)] | None = None  # vertical component, same samples
    vertical_units: str | None = None
    # units (and vertical_units) replace units the file's header states; without it a
    # contradiction is an error (a cm/s² file read as g gives a PGA 981 times too large)
    units_override: bool = False

    @field_validator("units", "vertical_units")
    @classmethod
    def _known_units(cls, v: str | None) -> str | None:
        if v is not None:
            try:
                units_to_si(v)
            except RecordError:
                raise ValueError(
                    f"unknown acceleration units {v!r}; use one of g, cm/s2 (gal), m/s2, mm/s2"
                ) from None
        return v

    @model_validator(mode="after")
    def _one_scaling(self) -> RecordConfig:
        if self.scale is not None and self.pga is not None:
            raise ValueError("give scale or pga, not both")
        if self.units_override and self.units is None and self.vertical_units is None:
            raise ValueError("units_override = true needs units (the units that replace the header's)")
        return self


class SinePulseConfig(_Section):
    """``shape = "sine"``: amplitude (m/s²), frequency (Hz), phase (rad, in [0, 2π))."""

    kind: Literal["pulse"]
    shape: Literal["sine"]
    amplitude: float
    frequency: Positive
    phase: Annotated[float, Field(ge=0, lt=2 * math.pi)] = 0.0


class CosinePulseConfig(_Section):
    """``shape = "cosine"``: amplitude (m/s²), frequency (Hz)."""

    kind: Literal["pulse"]
    shape: Literal["cosine"]
    amplitude: float
    frequency: Positive


class RectanglePulseConfig(_Section):
    """``shape = "rectangle"``: amplitude (m/s²), width (s)."""

    kind: Literal["pulse"]
    shape: Literal["rectangle"]
    amplitude: float
    width: Positive


class RickerPulseConfig(_Section):
    """``shape = "ricker"``: amplitude (m/s²), frequency (Hz), optional center (s)."""

    kind: Literal["pulse"]
    shape: Literal["ricker"]
    amplitude: float
    frequency: Positive
    center: Positive | None = None


_MOTION_KINDS = ("harmonic", "record", "pulse")
_PULSE_SHAPES = {
    "sine": SinePulseConfig,
    "cosine": CosinePulseConfig,
    "rectangle": RectanglePulseConfig,
    "ricker": RickerPulseConfig,
}
_MOTION_MODELS: dict[str, type[_Section]] = {
    "harmonic": HarmonicConfig,
    "record": RecordConfig,
    **{f"pulse:{shape}": model for shape, model in _PULSE_SHAPES.items()},
}


def _motion_tag(value: Any) -> str | None:
    """Which motion model validates ``value``: the kind, and for pulses also the shape."""
    if isinstance(value, Mapping):
        kind = value.get("kind")
        return f"pulse:{value.get('shape')}" if kind == "pulse" else kind
    if isinstance(value, BaseModel):
        kind = getattr(value, "kind", None)
        return f"pulse:{value.shape}" if kind == "pulse" else kind
    return None


MotionConfig = Annotated[
    Union[tuple(Annotated[model, Tag(tag)] for tag, model in _MOTION_MODELS.items())],  # noqa: UP007
    Discriminator(_motion_tag),
]


class SimulationConfig(_Section):
    """``[simulation]``: duration (s) and :class:`rocking.Options` fields. Without ``duration``
    a run lasts the motion plus free motion until everything is at rest (at most
    ``free_time_limit`` s)."""

    duration: Positive | None = None
    free_time_limit: NonNegative = _DEFAULTS.free_time_limit
    max_samples: Annotated[int, Field(ge=1)] = _DEFAULTS.max_samples
    gravity: Positive = _DEFAULTS.gravity
    normal_force: Literal["full", "paper"] = _DEFAULTS.normal_force  # type: ignore[assignment]
    impact: Literal["coulomb", "paper"] = _DEFAULTS.impact  # type: ignore[assignment]
    rtol: Positive = _DEFAULTS.rtol
    atol: Positive = _DEFAULTS.atol
    max_step: Positive = _DEFAULTS.max_step
    save_dt: Positive | None = _DEFAULTS.save_dt
    rest_velocity: Positive = _DEFAULTS.rest_velocity
    max_events: Annotated[int, Field(ge=1)] = _DEFAULTS.max_events
    stop_at_edge: bool = _DEFAULTS.stop_at_edge


class _RunConfig(_Section):
    """What the run files share: building ``[motion]`` and ``[simulation]``, and where the file
    came from. The subclasses declare the tables (in the order the reference lists them)."""

    # Where the config came from: for error messages and for relative record paths.
    _source: str | None = PrivateAttr(default=None)
    _base_dir: Path | None = PrivateAttr(default=None)

    @property
    def source(self) -> str | None:
        """The config file as the user named it (None for a dict)."""
        return self._source

    @property
    def base_dir(self) -> Path:
        """Folder against which relative record paths are resolved."""
        return self._base_dir if self._base_dir is not None else Path.cwd()

    def record_file(self) -> Path | None:
        """The resolved record file for ``kind = "record"``, else None.

        Raises
        ------
        ConfigError
            If the path is neither a file nor a bundled record.
        """
        if not isinstance(self.motion, RecordConfig):
            return None
        return _resolve_record_path(self.motion.path, self.base_dir, self._source)

    def _options(self) -> Options:
        sim, src = self.simulation, self._source
        with _field("simulation", src):
            return Options(
                gravity=sim.gravity,
                normal_force=sim.normal_force,
                impact=sim.impact,
                rtol=sim.rtol,
                atol=sim.atol,
                max_step=sim.max_step,
                rest_velocity=sim.rest_velocity,
                save_dt=sim.save_dt,
                max_events=sim.max_events,
                free_time_limit=sim.free_time_limit,
                stop_at_edge=sim.stop_at_edge,
                max_samples=sim.max_samples,
            )

    def _motion_spec(self) -> Any:
        m, src = self.motion, self._source
        if isinstance(m, RecordConfig):
            return self._record_spec(m)
        with _field("motion", src):
            if isinstance(m, HarmonicConfig):
                return Harmonic(
                    amplitude=m.amplitude,
                    frequency=m.frequency,
                    cycles=m.cycles,
                    form=m.form,
                    angular_frequency=m.angular_frequency,
                )
            if isinstance(m, SinePulseConfig):
                return SinePulse(amplitude=m.amplitude, frequency=m.frequency, phase=m.phase)
            if isinstance(m, CosinePulseConfig):
                return CosinePulse(amplitude=m.amplitude, frequency=m.frequency)
            if isinstance(m, RectanglePulseConfig):
                return RectanglePulse(amplitude=m.amplitude, width=m.width)
            if isinstance(m, RickerPulseConfig):
                return RickerPulse(amplitude=m.amplitude, frequency=m.frequency, center=m.center)
        raise AssertionError(f"unhandled motion model {type(m).__name__}")  # pragma: no cover

    def _record_spec(self, m: RecordConfig) -> Any:
        src = self._source
        file = self.record_file()
        try:
            record = read_record(file, format=m.format, units=m.units,
                                 units_override=m.units_override and m.units is not None)
        except UnitsConflictError as exc:
            raise ConfigError([("motion.units", _units_conflict(exc, "units"))], src) from None
        except RecordError as exc:
            # the reader's own text ("<file>: line <n>: ...") is what the user needs
            raise ConfigError([("motion.path", str(exc))], src) from None
        except ValueError as exc:  # unknown format= (units were checked by the model)
            raise ConfigError([("motion.format", str(exc))], src) from None
        except OSError as exc:
            raise ConfigError([("motion.path", f"cannot read {file}: {exc.strerror or exc}")], src) from None
        if m.vertical_path is not None:
            record = self._with_vertical(record, m)
        with _field("motion", src):
            if m.scale is not None:
                record = record.scaled(m.scale)
            elif m.pga is not None:
                record = record.scaled(pga=m.pga)
        return record


    def _with_vertical(self, record: Any, m: RecordConfig) -> Any:
        """The horizontal record with the vertical component of ``vertical_path`` attached; both
        must share their samples (the usual case for the components of one station)."""
        src = self._source
        file = _resolve_record_path(m.vertical_path, self.base_dir, src)
        try:
            vertical = read_record(file, format=m.format, units=m.vertical_units,
                                   units_override=m.units_override and m.vertical_units is not None)
        except UnitsConflictError as exc:
            raise ConfigError([("motion.vertical_units", _units_conflict(exc, "vertical_units"))], src) from None
        except RecordError as exc:
            raise ConfigError([("motion.vertical_path", str(exc))], src) from None
        except OSError as exc:
            raise ConfigError([("motion.vertical_path", f"cannot read {file}: {exc.strerror or exc}")], src) from None
        if vertical.time.size != record.time.size or not np.allclose(vertical.time, record.time, rtol=0, atol=1e-9):
            raise ConfigError(
                [("motion.vertical_path", f"{file} has {vertical.time.size} samples at dt = {vertical.dt} s; the "
                  f"horizontal record has {record.time.size} at dt = {record.dt} s: the components must share "
                  "their samples")],
                src,
            )
        return GroundMotion(time=record.time, values=record.values, vertical=vertical.values, name=record.name,
                            source=record.source, units=record.units, meta=dict(record.meta))


class Config(_RunConfig):
    """A validated run configuration of one statue (see the module docstring for the file layout).

    Build it with :func:`load_config`, which also resolves and reads a record so that
    every problem surfaces at load time; :meth:`to_specs` gives what
    :func:`rocking.simulate` takes.
    """

    statue: StatueConfig
    pedestal: PedestalConfig | None = None
    motion: MotionConfig
    simulation: SimulationConfig = SimulationConfig()

    def to_specs(self) -> tuple[System, Any, Options, float | None]:
        """Build the API objects.

        Returns
        -------
        system : rocking.System
        motion : rocking motion
            Harmonic, a pulse, or a :class:`~rocking.excitation.record.GroundMotion`.
        options : rocking.Options
        duration : float or None
            ``simulation.duration`` (s), or None: the motion, then free motion until everything
            is at rest (see :func:`rocking.simulate`).

        Raises
        ------
        ConfigError
            For any value the API refuses (e.g. a record file that cannot be read);
            the message names the file and the field.
        """
        src = self._source
        with _field("statue", src):
            top = self.statue.friction.to_spec() if self.statue.friction else None
            statue = Statue(
                width=self.statue.width,
                height=self.statue.height,
                mass=self.statue.mass,
                restitution=self.statue.restitution,
                friction=top,
            )
        pedestal = None
        if self.pedestal is not None:
            with _field("pedestal", src):
                pedestal = Pedestal(
                    mass=self.pedestal.mass,
                    friction=self.pedestal.friction.to_spec(),
                    width=self.pedestal.width,
                    height=self.pedestal.height,
                )
        with _field(None, src):
            system = System(statue=statue, pedestal=pedestal)
        return system, self._motion_spec(), self._options(), self.simulation.duration


class BlockConfig(_Section):
    """``[[blocks]]``: name, width and height (m), mass (kg), optional inertia (kg·m²) and offset (m)."""

    name: Annotated[str, Field(min_length=1)] | None = None
    width: Positive
    height: Positive
    mass: Positive
    inertia: Positive | None = None
    offset: float = 0.0


class InterfaceConfig(_Section):
    """``[[interfaces]]``: friction (omitted: never slips) and restitution (omitted: Housner's rule)."""

    friction: FrictionConfig | None = None
    restitution: Annotated[float, Field(ge=0, le=1)] | None = None


class StackConfig(_RunConfig):
    """A validated run configuration of a stack of blocks (``[[blocks]]``, ``[[interfaces]]``).

    Built by :func:`load_config` for a file with ``[[blocks]]``; :meth:`to_specs` gives what
    :func:`rocking.stack.simulate_stack` takes.
    """

    blocks: Annotated[list[BlockConfig], Field(min_length=1)]
    interfaces: list[InterfaceConfig]
    motion: MotionConfig
    simulation: SimulationConfig = SimulationConfig()

    @property
    def names(self) -> tuple[str, ...]:
        """The blocks' names, from the floor up ("block k" for a block without one)."""
        return tuple(b.name or f"block {i + 1}" for i, b in enumerate(self.blocks))

    def to_specs(self) -> tuple[Stack, Any, Options, float | None]:
        """Build the API objects: ``(stack, motion, options, duration)``, as :meth:`Config.to_specs`
        but with a :class:`rocking.stack.Stack` in place of the system.

        Raises
        ------
        ConfigError
            For a stack the engine cannot take (interfaces not one per block, blocks that do not
            overlap, a repeated name, the paper's normal force); the message
            names the file and the field.
        """
        src = self._source
        self._check_stack()
        blocks = []
        for i, b in enumerate(self.blocks):
            with _field(f"blocks[{i}]", src):
                blocks.append(Block(width=b.width, height=b.height, mass=b.mass, inertia=b.inertia,
                                    offset=b.offset, name=b.name or ""))
        interfaces = []
        for i, f in enumerate(self.interfaces):
            with _field(f"interfaces[{i}]", src):
                interfaces.append(Interface(friction=f.friction.to_spec() if f.friction else None,
                                            restitution=f.restitution))
        with _field(None, src):
            stack = Stack(blocks=tuple(blocks), interfaces=tuple(interfaces))
        return stack, self._motion_spec(), self._options(), self.simulation.duration

    def _check_stack(self) -> None:
        """What :class:`rocking.stack.Stack` refuses, said with the fields of the file."""
        src, names, blocks = self._source, self.names, self.blocks
        n, m = len(blocks), len(self.interfaces)
        if m != n:
            need = f"{n} blocks need {n} interfaces" if n > 1 else "1 block needs 1 interface"
            contacts = ", ".join(f"{below}–{name}" for below, name in zip(("floor",) + names[:-1], names))
            raise ConfigError([("interfaces", f"{need}, one [[interfaces]] per block from the floor up "
                                f"({contacts}), got {m}")], src)
        seen: dict[str, int] = {}
        for i, name in enumerate(names):
            if name in seen:
                raise ConfigError([(f"blocks[{i}].name", f"{name!r} is already the name of blocks[{seen[name]}]; "
                                    "the summary and the time series tell the blocks apart by name")], src)
            seen[name] = i
        for i in range(1, n):
            upper, lower = blocks[i], blocks[i - 1]
            limit = 0.5 * (upper.width + lower.width)
            if not abs(upper.offset) < limit:
                raise ConfigError([(f"blocks[{i}].offset", f"leaves no overlap with blocks[{i - 1}] ({names[i - 1]}) "
                                    f"below: |offset| must be < (width + width below)/2 = {limit:g} m, "
                                    f"got {_show(upper.offset)}")], src)
        value = self.simulation.normal_force
        if value != _DEFAULTS.normal_force:
            raise ConfigError([("simulation.normal_force", f"{value!r} (N = M g) is a model option of the "
                                "single-statue solver; a stack uses the contact forces it computes: remove it")], src)


def _units_conflict(exc: UnitsConflictError, key: str) -> str:
    """The reader's units contradiction in the words of the config file."""
    where = f"{exc.path}: line {exc.line}" if exc.line is not None else str(exc.path)
    return (
        f"{where}: the header states the units {exc.header_units!r}, but {key} = {exc.given_units!r}; "
        f"remove {key} to use the header's, or set units_override = true in [motion] if the header is wrong"
    )


# ----------------------------------------------------------------------------- loading
def load_config(
    config: str | os.PathLike[str] | Mapping[str, Any] | Config | StackConfig,
    *,
    base_dir: str | os.PathLike[str] | None = None,
) -> Config | StackConfig:
    """Read and validate a run configuration.

    Parameters
    ----------
    config : path-like, str, mapping, Config or StackConfig
        A TOML file, or a dict with the same tables. A loaded configuration is returned
        unchanged.
    base_dir : path-like, optional
        Folder for relative record paths; default: the TOML file's folder, or the
        current directory for a dict.

    Returns
    -------
    Config or StackConfig
        Validated (a :class:`StackConfig` for a file with ``[[blocks]]``); a record has been
        found and read once (so a bad file fails here).

    Raises
    ------
    ConfigError
        Unreadable or invalid TOML, unknown or missing keys, values out of range,
        a record that cannot be found or read. The message names the file and the
        dotted field.
    """
    if isinstance(config, (Config, StackConfig)):
        return config
    return load_config_and_specs(config, base_dir=base_dir)[0]


def load_config_and_specs(
    config: str | os.PathLike[str] | Mapping[str, Any] | Config | StackConfig,
    *,
    base_dir: str | os.PathLike[str] | None = None,
) -> tuple[Config | StackConfig, tuple[Any, Any, Options, float | None]]:
    """:func:`load_config`, and the API objects (``to_specs()``) its validation built: a run
    needs them, and building them again costs a tenth of a short simulation."""
    if isinstance(config, (Config, StackConfig)):
        return config, config.to_specs()
    if isinstance(config, Mapping):
        source, data = None, config
        # the working directory is already a physical path: resolving it again costs a tenth of load_config
        folder = Path(base_dir).resolve() if base_dir is not None else Path.cwd()
    elif isinstance(config, (str, os.PathLike)):
        source = os.fspath(config)
        data = _read_toml(Path(config), source)
        folder = Path(base_dir).resolve() if base_dir is not None else Path(config).resolve().parent
    else:
        raise ConfigError(
            [(None, f"a config is a TOML path or a dict, got {type(config).__name__}")]
        )
    model = _run_model(data, source)
    try:
        cfg = model.model_validate(data)
    except ValidationError as exc:
        raise ConfigError([_describe(err, model) for err in exc.errors()], source) from None
    cfg._source = source
    cfg._base_dir = folder
    specs = cfg.to_specs()  # surface record and spec errors now, not halfway through a batch
    return cfg, specs


def _run_model(data: Mapping[str, Any], source: str | None) -> type[Config] | type[StackConfig]:
    """:class:`StackConfig` for a file with ``[[blocks]]`` or ``[[interfaces]]``, else :class:`Config`."""
    if not isinstance(data, Mapping):
        return Config  # pydantic says what is wrong
    stack = [k for k in ("blocks", "interfaces") if k in data]
    if not stack:
        return Config
    single = [f"[{k}]" for k in ("statue", "pedestal") if k in data]
    if single:
        raise ConfigError([(stack[0], f"[[{stack[0]}]] describes a stack, which cannot also have "
                            f"{' or '.join(single)}: give either [statue] (and [pedestal]) or [[blocks]] and "
                            "[[interfaces]]")], source)
    return StackConfig


def _read_toml(path: Path, source: str) -> dict[str, Any]:
    try:
        with path.open("rb") as f:
            return tomllib.load(f)
    except FileNotFoundError:
        raise ConfigError([(None, "no such file")], source) from None
    except IsADirectoryError:
        raise ConfigError([(None, "is a directory, not a TOML file")], source) from None
    except tomllib.TOMLDecodeError as exc:
        raise ConfigError([(None, f"invalid TOML: {exc}")], source) from None
    except UnicodeDecodeError as exc:
        raise ConfigError([(None, f"not UTF-8 text ({exc.reason} at byte {exc.start})")], source) from None
    except OSError as exc:
        raise ConfigError([(None, f"cannot read: {exc.strerror or exc}")], source) from None


def _resolve_record_path(path: str, base_dir: Path, source: str | None) -> Path:
    """A record file: absolute, relative to the config's folder, or a bundled name.

    The current directory is deliberately not searched: a config must mean the same
    thing wherever it is run from.
    """
    p = Path(path).expanduser()
    candidate = p if p.is_absolute() else base_dir / p
    if candidate.is_file():
        return candidate
    records = bundled_records()
    lookup = {**{q.name: q for q in records.values()}, **records}
    if path in lookup:
        return lookup[path]
    folded = [k for k in lookup if k.lower() == path.lower()]
    if len(folded) == 1:
        return lookup[folded[0]]
    close = difflib.get_close_matches(path, list(records), n=3, cutoff=0.5)
    hint = f"; did you mean {', '.join(close)}?" if close else ""
    where = str(candidate) if p.is_absolute() else f"{path!r} in {base_dir}"
    raise ConfigError(
        [
            (
                "motion.path",
                f"record not found: no file {where} and no bundled record of that name"
                f"{hint} (`rocking records` lists the bundled ones)",
            )
        ],
        source,
    )


# ------------------------------------------------------------------------------ errors
def _bound(value: Any) -> str:
    """A limit from a constraint: 0 rather than 0.0 (pydantic stores float limits)."""
    if isinstance(value, float) and value.is_integer():
        return str(int(value))
    return repr(value)


def _show(value: Any) -> str:
    """A value as the user wrote it: -1, 0.5, 'tan', true."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, Mapping):
        return "a table"
    if isinstance(value, (list, tuple)):
        return "an array"
    return repr(value)


def _loc_to_field(loc: tuple[Any, ...]) -> str:
    """Dotted field from a pydantic location, without the motion union's tag."""
    parts = list(loc)
    if len(parts) > 1 and parts[0] == "motion" and parts[1] in _MOTION_MODELS:
        del parts[1]
    # a key with control characters ("\r") is shown quoted, or it would be invisible; an entry of
    # an array of tables as [i]: blocks[1].width
    out = ""
    for p in parts:
        if isinstance(p, int):
            out += f"[{p}]"
        else:
            out += ("." if out else "") + (str(p) if str(p) and str(p).isprintable() else repr(str(p)))
    return out


def _model_at(loc: tuple[Any, ...], root: type[BaseModel] = Config) -> type[BaseModel] | None:
    """The model that owns the keys of the table at ``loc`` (for "did you mean")."""
    model: type[BaseModel] | None = root
    i = 0
    while model is not None and i < len(loc):
        key = loc[i]
        if isinstance(key, int):  # an entry of an array of tables: the same model
            i += 1
            continue
        if model is root and key == "motion":
            tag = loc[i + 1] if i + 1 < len(loc) else None
            model = _MOTION_MODELS.get(tag)  # type: ignore[arg-type]
            i += 2
            continue
        field = model.model_fields.get(key)  # type: ignore[arg-type]
        if field is None:
            return None
        model = next(
            (a for a in _flatten(field.annotation) if isinstance(a, type) and issubclass(a, BaseModel)),
            None,
        )
        i += 1
    return model


def _flatten(annotation: Any) -> Iterator[Any]:
    args = getattr(annotation, "__args__", None)
    if args:
        for a in args:
            yield from _flatten(a)
    else:
        yield annotation


_TYPE_WORDS = {
    "float_type": "a number",
    "float_parsing": "a number",
    "int_type": "an integer",
    "int_parsing": "an integer",
    "int_from_float": "an integer",
    "string_type": "a string",
    "bool_type": "true or false",
    "model_type": "a table",
    "model_attributes_type": "a table",
    "dict_type": "a table",
    "list_type": "an array",
}


def _describe(err: Mapping[str, Any], root: type[BaseModel] | None = None) -> tuple[str | None, str]:
    """One pydantic error -> (dotted field, message in plain words); ``root`` is the run file's
    model (:class:`Config` or :class:`StackConfig`), None for the other files."""
    kind, loc, ctx = err["type"], tuple(err["loc"]), err.get("ctx") or {}
    value = err.get("input")
    field = _loc_to_field(loc) or None
    if kind == "missing":
        if loc == ("statue",) and root is Config:
            return field, "missing (required); or describe a stack of blocks with [[blocks]] and [[interfaces]]"
        return field, "missing (required)"
    if kind == "extra_forbidden":
        owner = _model_at(loc[:-1], root or Config)
        known = list(owner.model_fields) if owner is not None else []
        close = difflib.get_close_matches(str(loc[-1]), known, n=1, cutoff=0.6)
        hint = f"; did you mean {close[0]!r}?" if close else (
            f"; known keys: {', '.join(known)}" if known else ""
        )
        return field, f"unknown key{hint}"
    if kind in ("union_tag_invalid", "union_tag_not_found"):
        return _describe_motion_tag(value)
    if kind == "greater_than":
        return field, f"must be > {_bound(ctx['gt'])}, got {_show(value)}"
    if kind == "greater_than_equal":
        return field, f"must be >= {_bound(ctx['ge'])}, got {_show(value)}"
    if kind == "less_than":
        return field, f"must be < {_bound(ctx['lt'])}, got {_show(value)}"
    if kind == "less_than_equal":
        return field, f"must be <= {_bound(ctx['le'])}, got {_show(value)}"
    if kind == "finite_number":
        return field, f"must be a finite number, got {_show(value)}"
    if kind == "literal_error":
        return field, f"must be one of {ctx['expected']}, got {_show(value)}"
    if kind in ("string_too_short", "too_short"):
        return field, "must not be empty"
    if kind == "list_type" and loc in (("blocks",), ("interfaces",)):
        return field, f"must be an array of tables (one [[{loc[0]}]] per entry), got {_show(value)}"
    if kind in _TYPE_WORDS:
        return field, f"must be {_TYPE_WORDS[kind]}, got {_show(value)}"
    msg = str(err["msg"])
    msg = re.sub(r"^(Value error|Assertion failed), ", "", msg)
    return field, msg


def _describe_motion_tag(value: Any) -> tuple[str | None, str]:
    kinds = ", ".join(repr(k) for k in _MOTION_KINDS)
    if not isinstance(value, Mapping):
        return "motion", f"must be a table, got {_show(value)}"
    if "kind" not in value:
        return "motion.kind", f"missing (required); use one of {kinds}"
    kind = value["kind"]
    if kind != "pulse":
        return "motion.kind", f"unknown motion kind {_show(kind)}; use one of {kinds}"
    shapes = ", ".join(repr(s) for s in _PULSE_SHAPES)
    if "shape" not in value:
        return "motion.shape", f"missing (required) for a pulse; use one of {shapes}"
    return "motion.shape", f"unknown pulse shape {_show(value['shape'])}; use one of {shapes}"


# An API message that starts with a field name: "statue.width must be ...",
# "frequency must be ..." -> ("statue.width", "must be ...").
_LEADING_NAME = re.compile(r"^([A-Za-z_][\w.]*) (must .*)$", re.S)


@contextmanager
def _field(section: str | None, source: str | None) -> Iterator[None]:
    """Turn a spec class's ValueError into a ConfigError that names the field."""
    try:
        yield
    except ConfigError:
        raise
    except ValueError as exc:
        text = str(exc)
        m = _LEADING_NAME.match(text)
        if m is None:
            raise ConfigError([(section, text)], source) from None
        name, rest = m.groups()
        if section and not name.startswith(f"{section}."):
            name = f"{section}.{name}"
        raise ConfigError([(name, rest)], source) from None
