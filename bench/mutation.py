"""On-demand mutation testing of the physics modules with cosmic-ray (not part of CI).

How to run it, how long it takes and how to read it: bench/MUTATION.md.

Everything happens in a copy of the repository (default /tmp/rocking-mutation/tree): cosmic-ray
writes each mutant over the module file, and a mutated file in the working tree would break
whoever else is running the tests there. The copy is imported through PYTHONPATH, and a pytest
plugin written next to it checks, in every test run, that ``rocking`` really comes from the copy.

Numba keeps compiled code on disk and checks only the source file of each cached function, not
the files of the functions it calls or of the constants it reads. So every mutant runs with a
fresh NUMBA_CACHE_DIR: the worker's folder is emptied and refilled from a cache warmed on the
unmutated copy, minus the entries of the mutated module and of every compiled module that depends
on it (through the names it imports, followed transitively; see ``stale_modules``). A mutant of a
module no compiled code reads (``contact/friction.py``, ``excitation/pulses.py``) thus costs a
test run, not a 35 s recompilation of the solver, and a mutant of ``contact/impact.py`` recompiles
impact, transitions and the solver core.
"""

from __future__ import annotations

import argparse
import ast
import difflib
import json
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
DEFAULT_WORK = Path(tempfile.gettempdir()) / "rocking-mutation"
SHARE_FILE = "share.txt"  # other work folders whose results this one reuses (`run --share`)
MIRRORED = "not run again: the outcome of"

# Module (under src/rocking) -> the test files that exercise it, most direct and fastest first:
# pytest runs with -x, so a killed mutant usually stops within the first file. A file missing
# from the copy is left out. (tests/test_oracles_selfcheck.py never imports rocking: it checks
# the oracles, so it kills no mutant and is in no list.)
MODULES: dict[str, list[str]] = {
    "contact/impact.py": [
        "test_mutants.py", "test_impact_maps.py", "test_independent_solver.py", "test_statue_on_pedestal.py",
        "test_single_block_rocking.py", "test_sliding_and_slide_rock.py", "test_paper.py",
    ],
    "contact/friction.py": [
        "test_mutants.py", "test_input_errors.py", "test_config.py", "test_sliding_and_slide_rock.py",
        "test_statue_on_pedestal.py",
    ],
    "excitation/pulses.py": [
        "test_mutants.py", "test_floor_signals.py", "test_config.py", "test_input_errors.py",
        "test_single_block_rocking.py", "test_fast_paths.py", "test_integrator_crosscheck.py", "test_run_until_rest.py",
    ],
    "excitation/signal.py": [
        "test_mutants.py", "test_independent_solver.py", "test_floor_signals.py", "test_fast_paths.py", "test_single_block_rocking.py",
        "test_sliding_and_slide_rock.py", "test_statue_on_pedestal.py", "test_integrator_crosscheck.py",
        "test_records.py", "test_run_until_rest.py", "test_settle_claims.py",
    ],
    "models/modes.py": [
        "test_mutants.py", "test_independent_solver.py", "test_fast_paths.py", "test_single_block_rocking.py", "test_sliding_and_slide_rock.py",
        "test_statue_on_pedestal.py", "test_run_until_rest.py",
    ],
    "models/dynamics.py": [
        "test_mutants.py", "test_independent_solver.py", "test_statue_on_pedestal.py", "test_single_block_rocking.py",
        "test_sliding_and_slide_rock.py", "test_fast_paths.py", "test_integrator_crosscheck.py", "test_settle_claims.py",
    ],
    "models/transitions.py": [
        "test_mutants.py", "test_impact_beyond_friction.py", "test_independent_solver.py", "test_single_block_rocking.py", "test_sliding_and_slide_rock.py",
        "test_statue_on_pedestal.py", "test_run_until_rest.py",
    ],
    "models/parameters.py": [
        "test_independent_solver.py", "test_single_block_rocking.py", "test_statue_on_pedestal.py", "test_sliding_and_slide_rock.py",
    ],
    "models/bodies.py": [
        "test_mutants.py", "test_input_errors.py", "test_config.py", "test_single_block_rocking.py", "test_statue_on_pedestal.py",
        "test_sliding_and_slide_rock.py",
    ],
    "excitation/harmonic.py": [
        "test_mutants.py", "test_config.py", "test_single_block_rocking.py", "test_fast_paths.py", "test_integrator_crosscheck.py",
    ],
    "excitation/record.py": ["test_mutants.py", "test_records.py", "test_config.py", "test_single_block_rocking.py"],
    "solver/compiled.py": [
        "test_compiled_root_finders.py", "test_mutants.py", "test_impact_beyond_friction.py", "test_fast_paths.py", "test_single_block_rocking.py", "test_sliding_and_slide_rock.py",
        "test_statue_on_pedestal.py", "test_integrator_crosscheck.py", "test_crosscheck_mutants.py",
        "test_run_until_rest.py", "test_settle_claims.py", "test_interrupts.py",
        # the stack engine's half of this file cannot see a mutant of the two-body solver
        "test_compiled_bounds.py::test_the_solver_core_stays_inside_its_arrays",
        # the two-body need in a step an impact cuts, against its saved forces (thirtieth round)
        "test_stack_engine.py::test_the_friction_a_rocking_block_needs_just_before_an_impact_is_found_in_the_step_the_impact_cuts",
    ],
    "solver/crosscheck.py": ["test_integrator_crosscheck.py", "test_crosscheck_mutants.py"],
    "io/records.py": ["test_mutants.py", "test_records.py", "test_fuzz_inputs.py", "test_config.py"],
    "models/regimes.py": ["test_mutants.py", "test_single_block_rocking.py", "test_statue_on_pedestal.py", "test_run_until_rest.py"],
    "excitation/base.py": ["test_mutants.py", "test_floor_signals.py", "test_single_block_rocking.py", "test_records.py",
                           "test_integrator_crosscheck.py"],
    "excitation/_checks.py": ["test_mutants.py", "test_input_errors.py", "test_config.py", "test_fuzz_inputs.py"],
    "solver/signals.py": ["test_mutants.py", "test_interrupts.py"],
    "solver/warmup.py": ["test_compiled_bounds.py", "test_install.py", "test_cli.py"],
    "solver/__init__.py": ["test_install.py", "test_single_block_rocking.py"],
    # The stack engine (issue 11): its own tests first, then the cross-checks against the
    # two-body solver and the Moreau–Jean solver, then the studies that read its summaries. The
    # mode selection's own oracle (and the corners' closed form) come first: they compile the
    # selection alone, ~45 s, where the engine's tests recompile the whole engine, ~15 min a
    # mutant beside another worker.
    "stack/kinematics.py": ["test_stack_corners.py", "test_stack_modes.py", "test_stack_engine_parts.py",
                            "test_stack_engine.py", "test_stack_crosscheck.py", "test_stack_timestepping.py"],
    # lcp.py is plain Python read by the Moreau–Jean solver only: its oracle, then that solver's
    # own tests (the cross-check, 5 min a run, is left to `try`)
    "stack/lcp.py": ["test_lcp.py", "test_stack_timestepping.py"],
    "stack/modes.py": ["test_stack_corners.py", "test_stack_modes.py", "test_stack_engine_parts.py",
                       "test_stack_engine.py", "test_stack_crosscheck.py", "test_stack_timestepping.py"],
    # The engine's parts one at a time first (seconds: only the helpers a test calls compile),
    # then whole runs (each recompiles the engine, ~8 min a mutant).
    "stack/engine.py": ["test_stack_engine_parts.py", "test_stack_engine.py", "test_stack_crosscheck.py",
                        "test_stack_timestepping.py"],
    "stack/model.py": ["test_stack_config.py", "test_stack_engine.py", "test_input_errors.py"],
    "stack/simulate.py": ["test_settle_claims.py", "test_stack_engine.py", "test_stack_crosscheck.py", "test_design_stack.py", "test_report_stack.py"],
    "stack/timestepping.py": ["test_stack_timestepping.py"],
    # The Runge–Kutta toolkits both cores share: their unit tests compile small drivers of their
    # own (against SciPy's steps, the bitwise partial steps, the root searches on built polynomials),
    # so a mutant costs seconds of compilation, not the solver's minutes.
    "integrators/dop853.py": ["test_partial_steps.py", "test_dop853.py", "test_compiled_root_finders.py",
                              "test_dopri5.py"],
    "integrators/dopri5.py": ["test_partial_steps.py", "test_dopri5.py"],
}

# Whole runs of the stack engine that pass uncompiled in seconds (each under 12 s in the
# interpreter on the 2-CPU machine with two workers busy, 2026-12-07; about 2 min for the 58 in
# all): with them, a mutant of the step loop or of the event handling that the parts' tests let
# through is judged in the interpreter too, where it paid a recompilation of the engine (~4 min)
# and the compiled runs. The first 19 run, uncompiled, every line of engine.py that the 58 run
# (1331 of its 1397 statements with the first 56, on ea78182, `coverage stack/engine.py`; the
# parts' tests alone ran 934 of 1383): they come first, so that a mutant there fails early. The rest of test_stack_engine.py (the
# random stacks, the records at full scale, the long chatters) stays compiled.
ENGINE_RUNS = [f"test_stack_engine.py::{name}" for name in (
    "test_flight_when_a_record_drops_the_floor_through_minus_g_along_a_steep_ramp",
    "test_an_impact_that_would_make_a_corner_pull_holds_it",
    "test_onset_stack_rocks_as_one",
    "test_a_corner_at_one_edge_is_not_taken_for_one_passing_it_when_the_other_corner_passes_the_other_edge_first",
    "test_a_block_pushed_partly_past_the_edge_stops_there_overhanging",
    "test_bad_stack_inputs_name_the_field",
    "test_a_block_flush_with_the_edge_below",
    "test_a_block_sliding_to_the_edge_stops_the_run_undetermined_when_asked",
    "test_a_run_that_fills_its_event_budget_stops_at_that_event_undetermined",
    "test_a_frictionless_face_slides_from_the_first_instant_the_floor_pushes",
    "test_flight_when_a_vertical_harmonic_first_reaches_minus_g",
    "test_a_block_at_rest_slips_where_a_ricker_pulse_first_exceeds_its_friction",
    "test_a_block_at_a_harmonic_crest_just_above_its_threshold_rocks_lands_and_peaks_as_its_closed_form_says",
    "test_a_light_block_at_rest_needs_the_floors_peak_over_g",
    "test_a_run_whose_blocks_overlap_gives_no_verdict",
    "test_the_friction_an_impact_needs_counts_in_the_interfaces_need",
    "test_a_run_of_no_positive_finite_duration_is_refused",
    "test_an_impact_whose_restitution_has_no_consistent_mode_restitutes_less",
    "test_paper_normal_force_is_refused_for_stacks",
    "test_a_block_a_hair_wider_than_its_plinth_slides_over_both_edges_tips_and_falls_off",
    "test_a_block_at_rest_slips_at_the_first_crest_above_its_friction_wherever_it_falls_in_a_step",
    "test_a_block_set_rocking_just_before_a_sample_where_the_floor_turns_back_lands_when_its_closed_form_says",
    "test_a_block_slides_past_the_edge_tips_over_it_and_falls_off",
    "test_a_column_of_drums_rocking_as_one_restitutes_as_the_one_block",
    "test_a_gap_that_closes_and_opens_again_before_the_first_sample_is_an_impact",
    "test_a_jump_of_the_floor_motion_that_breaks_the_grip_starts_the_slip_at_the_jump",
    "test_a_mode_solve_satisfies_the_equations_of_that_mode",
    "test_a_record_is_saved_at_its_own_sample_interval_unless_asked_otherwise",
    "test_a_slipping_interface_that_rocks_onto_the_lower_blocks_corner_keeps_its_slip",
    "test_a_stack_that_never_moves_reports_no_energy_balance_error",
    "test_an_impact_that_leaves_another_interface_rocking_slower_than_rest_lands_it",
    "test_an_impact_that_stops_a_slow_slip_creates_no_energy",
    "test_an_impulse_is_split_along_the_face_of_the_block_it_crosses_onto",
    "test_energy_balance_and_dissipation",
    "test_enough_top_friction_changes_nothing",
    "test_flight_when_the_floor_falls_faster_than_gravity",
    "test_friction_never_creates_energy_in_a_three_block_stack",
    "test_mirror_symmetry",
    "test_onset_stack_slides_on_floor",
    "test_onset_upper_block_rocks_first",
    "test_onset_upper_block_slides_first",
    "test_similarity_law",
    "test_single_block_matches_todays_solver",
    "test_sliding_block_matches_todays_solver",
    "test_stack_rocks_as_one_composite_body",
    "test_statue_on_sliding_pedestal_matches_todays_solver",
    "test_statue_on_sliding_pedestal_under_a_record_matches_todays_solver",
    "test_statue_slipping_on_a_held_pedestal_moves_as_todays_sliding_block",
    "test_the_contact_states_are_saved_in_their_own_columns",
    "test_the_friction_a_face_needs_stops_counting_once_the_block_under_it_topples",
    "test_the_friction_a_rocking_block_needs_is_its_peak_between_the_samples",
    "test_the_friction_a_rocking_block_needs_peaks_just_before_an_impact_as_its_saved_forces_show",
    "test_the_friction_a_stack_at_rest_needs_under_a_harmonic_or_a_pulse_is_its_peak_over_g",
    "test_the_friction_a_stack_at_rest_needs_under_a_record_is_the_floor_s",
    "test_the_relative_energy_error_of_a_light_stack_is_reported",
    "test_the_run_is_called_as_documented_and_its_result_is_read_only",
    "test_the_sink_check_sees_a_block_tilted_far_on_the_one_below",
    "test_the_sink_check_sees_the_corners_of_drums_of_equal_width",
)]

# Module -> test files run first *in the interpreter* (NUMBA_DISABLE_JIT=1): the @njit functions
# run as plain Python, so nothing is compiled. A mutant these tests kill costs seconds instead of
# a recompilation of the solver core (~40 s) plus the compiled tests; one they let through goes
# on to the compiled tests of MODULES as before. The interpreter also checks every index, which
# compiled code does not (a write past an array's end is a kill here, as in
# tests/test_dop853.py). Only files that pass unmutated in the interpreter belong here (the
# baseline checks it): not the signal tests, whose compiled loop must be interrupted mid-run.
UNCOMPILED: dict[str, list[str]] = {
    "solver/compiled.py": [
        "test_fast_paths.py", "test_single_block_rocking.py", "test_independent_solver.py",
        "test_sliding_and_slide_rock.py", "test_statue_on_pedestal.py", "test_integrator_crosscheck.py",
        "test_crosscheck_mutants.py", "test_compiled_root_finders.py", "test_mutants.py",
    ],
    # The stack engine's fast oracles pass uncompiled in ~15 s, then its whole runs that are quick
    # in the interpreter (ENGINE_RUNS); the random stacks and the long runs stay compiled.
    "stack/kinematics.py": ["test_stack_corners.py", "test_stack_modes.py", "test_stack_engine_parts.py",
                            *ENGINE_RUNS],
    "stack/modes.py": ["test_stack_corners.py", "test_stack_modes.py", "test_stack_engine_parts.py", *ENGINE_RUNS],
    "stack/engine.py": ["test_stack_engine_parts.py", *ENGINE_RUNS],
}
INTERPRETED = "killed in the interpreter (NUMBA_DISABLE_JIT=1), before any compilation"
INTERPRETER_CUT = "the interpreter stage ran past"
# A mutant that only slows a run down (more steps, a longer search) can make the interpreted run
# crawl where compiled code would finish: the interpreter stage gets this many times its own
# unmutated time (at least INTERPRETER_MIN_S), then gives way to the compiled tests, which judge.
INTERPRETER_FACTOR = 3.0
INTERPRETER_MIN_S = 120.0
INTERPRETER_DEFAULT_S = 240.0  # a session whose baseline did not time the stage

# One meaningful mutant per site, as mutmut makes, instead of cosmic-ray's every-operator-to-every-
# operator cross product (12 mutants per `*`, most of them type errors that any test kills). A
# comparison gets its negation and its boundary shift; arithmetic its inverse operation.
KEEP_OPERATORS = {
    "core/ReplaceBinaryOperator_Add_Sub", "core/ReplaceBinaryOperator_Sub_Add",
    "core/ReplaceBinaryOperator_Mul_Div", "core/ReplaceBinaryOperator_Div_Mul",
    "core/ReplaceBinaryOperator_FloorDiv_Div", "core/ReplaceBinaryOperator_Mod_FloorDiv",
    "core/ReplaceBinaryOperator_Pow_Mul",
    "core/ReplaceComparisonOperator_Lt_GtE", "core/ReplaceComparisonOperator_Lt_LtE",
    "core/ReplaceComparisonOperator_LtE_Gt", "core/ReplaceComparisonOperator_LtE_Lt",
    "core/ReplaceComparisonOperator_Gt_LtE", "core/ReplaceComparisonOperator_Gt_GtE",
    "core/ReplaceComparisonOperator_GtE_Lt", "core/ReplaceComparisonOperator_GtE_Gt",
    "core/ReplaceComparisonOperator_Eq_NotEq", "core/ReplaceComparisonOperator_NotEq_Eq",
    "core/ReplaceComparisonOperator_Is_IsNot", "core/ReplaceComparisonOperator_IsNot_Is",
    "core/ReplaceUnaryOperator_Delete_USub", "core/ReplaceUnaryOperator_Delete_Not",
    "core/AddNot", "core/ReplaceTrueWithFalse", "core/ReplaceFalseWithTrue",
    "core/ReplaceAndWithOr", "core/ReplaceOrWithAnd",
    "core/ReplaceBreakWithContinue", "core/ReplaceContinueWithBreak",
    "core/NumberReplacer", "core/ZeroIterationForLoop", "core/ExceptionReplacer",
    # NumberReplacer makes n+1 and n-1 of each number; only n+1 is run (see init_session).
    # Not kept: RemoveDecorator (without @njit a function computes the same thing in Python, or
    # fails to type in its compiled caller: no physics is tested either way), the unary
    # swaps other than deletion, and the parameterised VariableReplacer/VariableInserter.
}

GUARD_PLUGIN = "rocking_mutation_guard"
_GUARD_SOURCE = '''"""Written by bench/mutation.py: stop at once if rocking is imported from anywhere but the copy."""
import os

import rocking


def pytest_sessionstart(session):
    expected = os.environ["ROCKING_MUTATION_SRC"]
    if not os.path.realpath(rocking.__file__).startswith(os.path.realpath(expected) + os.sep):
        raise SystemExit(f"rocking imported from {rocking.__file__}, not from the copy {expected}")
'''


# ---------------------------------------------------------------------------------------------
# Which compiled modules a change to a module can leave stale in numba's cache


def _module_file(src: Path, dotted: str) -> Path | None:
    base = src.joinpath(*dotted.split("."))
    if base.with_suffix(".py").is_file():
        return base.with_suffix(".py")
    if (base / "__init__.py").is_file():
        return base / "__init__.py"
    return None


class _Module:
    """What the cache analysis needs of one module: is it compiled, what it imports, its bindings."""

    def __init__(self, src: Path, path: Path):
        self.rel = path.relative_to(src / "rocking").as_posix()
        self.tree = ast.parse(path.read_text(encoding="utf-8"))
        parts = list(path.relative_to(src).with_suffix("").parts)
        package = parts[:-1]  # the package a relative import starts from, for a module and an __init__ alike
        self.imports: dict[str, tuple[Path, str | None]] = {}  # local name -> (module file, name or None)
        self.compiled = False
        for node in self.tree.body:
            if isinstance(node, ast.ImportFrom):
                if node.level:
                    anchor = package[: len(package) - node.level + 1]
                    dotted = ".".join(anchor + ([node.module] if node.module else []))
                else:
                    dotted = node.module or ""
                if dotted.split(".")[0] == "numba":
                    self.compiled = True
                target = _module_file(src, dotted)
                if target is None:
                    continue
                for alias in node.names:
                    sub = _module_file(src, f"{dotted}.{alias.name}")
                    local = alias.asname or alias.name
                    self.imports[local] = (sub, None) if sub is not None else (target, alias.name)
            elif isinstance(node, ast.Import):
                for alias in node.names:
                    if alias.name.split(".")[0] == "numba":
                        self.compiled = True
                    target = _module_file(src, alias.name)
                    if target is not None:
                        self.imports[(alias.asname or alias.name).split(".")[0]] = (target, None)

    def binding(self, name: str) -> ast.stmt | None:
        for node in self.tree.body:
            targets: list[ast.AST] = []
            if isinstance(node, (ast.FunctionDef, ast.ClassDef)) and node.name == name:
                return node
            if isinstance(node, ast.Assign):
                targets = node.targets
            elif isinstance(node, ast.AnnAssign):
                targets = [node.target]
            for target in targets:
                if any(isinstance(n, ast.Name) and n.id == name for n in ast.walk(target)):
                    return node
        return None


def _modules(src: Path) -> dict[Path, _Module]:
    mods = {}
    for p in sorted((src / "rocking").rglob("*.py")):
        try:
            mods[p] = _Module(src, p)
        except SyntaxError:  # a file being written: nothing that runs can import it either
            print(f"warning: {p} does not parse; left out of the cache analysis", file=sys.stderr)
    return mods


def _deps(mods: dict[Path, _Module], path: Path, name: str | None, seen: set) -> set[Path]:
    """Module files whose source can change the compiled code or the constant reached through
    ``path`` (and ``name`` in it; None = the whole module). Over-approximates: a compiled module
    depends on everything it imports (its callees are linked into its cache entries); a plain
    module's constant depends on the module and on what its binding statement mentions."""
    key = (path, name)
    if key in seen:
        return set()
    seen.add(key)
    mod = mods[path]
    out = {path}
    if mod.compiled or name is None:
        for target, sub in mod.imports.values():
            out |= _deps(mods, target, sub, seen)
        return out
    stmt = mod.binding(name)
    if stmt is None:  # re-exported or built dynamically: take all of it
        if name in mod.imports:
            target, sub = mod.imports[name]
            return out | _deps(mods, target, sub, seen)
        return out | _deps(mods, path, None, seen)
    for node in ast.walk(stmt):
        if isinstance(node, ast.Name) and node.id in mod.imports:
            target, sub = mod.imports[node.id]
            out |= _deps(mods, target, sub, seen)
    return out


def stale_modules(src: Path, mutated: str) -> set[str]:
    """Compiled modules (paths under src/rocking) whose cached code a change to ``mutated`` can
    invalidate: the module itself if compiled, and every compiled module depending on it."""
    mods = _modules(src)
    target = src / "rocking" / mutated
    stale = {mutated} if mods[target].compiled else set()
    for path, mod in mods.items():
        if mod.compiled and target in _deps(mods, path, None, set()):
            stale.add(mod.rel)
    return stale


def _fill_cache(base: Path, dest: Path, tree_src: Path, stale: set[str]) -> None:
    """Empty ``dest`` and refill it from ``base`` without the entries of the ``stale`` modules.
    Numba stores the cache of /x/y/m.py under NUMBA_CACHE_DIR/x/y/ as files named m.<qualname>-..."""
    shutil.rmtree(dest, ignore_errors=True)
    dest.mkdir(parents=True)
    if not base.is_dir():
        return
    # numba's own rule for the folder of a source file's entries (its name changed across versions)
    from numba.core.caching import _CacheLocator

    drop: dict[str, set[str]] = {}
    for rel in stale:
        f = (tree_src / "rocking" / rel).resolve()
        drop.setdefault(_CacheLocator.get_suitable_cache_subpath(str(f)), set()).add(f.stem + ".")
    dropped: set[str] = set()

    def ignore(folder, names):
        prefixes = drop.get(os.path.relpath(folder, base), ())
        out = [n for n in names if any(n.startswith(p) for p in prefixes)]
        dropped.update(os.path.relpath(folder, base) + "/" + n.split(".")[0] for n in out)
        return out

    shutil.copytree(base, dest, ignore=ignore, dirs_exist_ok=True)
    # The tests compile the mutated module or its dependents, so a warmed cache has entries of some
    # stale module: if none was found, the layout has changed and the mutant would run on stale
    # compiled code, so stop rather than report it as survived.
    missing = {(sub, p) for sub, prefixes in drop.items() for p in prefixes} - {
        (d.rsplit("/", 1)[0], d.rsplit("/", 1)[1] + ".") for d in dropped}
    if drop and not dropped and any(base.iterdir()):
        raise SystemExit(f"numba cache layout not understood: no entries for {sorted(missing)} in {base}")


# ---------------------------------------------------------------------------------------------
# The copy of the repository


class Work:
    def __init__(self, root: Path):
        self.root = root
        self.tree = root / "tree"
        self.pristine = root / "pristine"  # the copy's src/ as copied (mtimes kept), to undo leftovers
        self.base_cache = root / "numba-base"
        self.worker_cache = root / "numba-worker0"
        self.plugin_dir = root / "plugin"
        self.sessions = root / "sessions"

    def slug(self, module: str) -> str:
        return module.replace("/", "_").removesuffix(".py")

    def config(self, module: str) -> Path:
        return self.sessions / f"{self.slug(module)}.toml"

    def db(self, module: str) -> Path:
        return self.sessions / f"{self.slug(module)}.sqlite"

    def meta(self, module: str) -> Path:
        return self.sessions / f"{self.slug(module)}.json"

    def env(self, cache: Path, tree: Path | None = None) -> dict:
        tree = tree or self.tree
        env = dict(os.environ)
        env.update(
            PYTHONPATH=os.pathsep.join([str(tree / "src"), str(self.plugin_dir)]),
            ROCKING_MUTATION_SRC=str(tree / "src"),
            NUMBA_CACHE_DIR=str(cache),
            PYTHONDONTWRITEBYTECODE="1",
            # one core: the other one belongs to whoever else uses the machine
            NUMBA_NUM_THREADS="1", OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1", MKL_NUM_THREADS="1",
        )
        return env


def prepare(work: Work, force: bool) -> None:
    """Copy the working tree (tracked and untracked, not ignored files) to ``work.tree``."""
    if work.tree.exists() and not force:
        restore(work)
        return
    for p in (work.tree, work.pristine, work.base_cache, work.worker_cache, work.sessions, work.plugin_dir):
        shutil.rmtree(p, ignore_errors=True)
    listed = subprocess.run(
        ["git", "-C", str(REPO), "ls-files", "-co", "--exclude-standard", "-z"],
        check=True, capture_output=True,
    ).stdout.decode().split("\0")
    for rel in filter(None, listed):
        src = REPO / rel
        if src.is_file():
            dst = work.tree / rel
            dst.parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(src, dst)
    shutil.copytree(work.tree / "src", work.pristine)
    work.plugin_dir.mkdir(parents=True)
    (work.plugin_dir / f"{GUARD_PLUGIN}.py").write_text(_GUARD_SOURCE)
    work.sessions.mkdir(parents=True)
    head = subprocess.run(["git", "-C", str(REPO), "rev-parse", "HEAD"], capture_output=True, text=True).stdout
    dirty = subprocess.run(["git", "-C", str(REPO), "status", "--short", "src"], capture_output=True, text=True).stdout
    (work.root / "SOURCE.txt").write_text(f"copied {time.strftime('%Y-%m-%d %H:%M')} from {REPO}\nHEAD {head}"
                                          f"uncommitted changes under src/:\n{dirty or '(none)'}\n")
    print(f"copied {REPO} to {work.tree}")


def restore(work: Work) -> None:
    """Put back any module an interrupted run left mutated (with its original mtime, which numba's
    cache index checks)."""
    for f in work.pristine.rglob("*.py"):
        dst = work.tree / "src" / f.relative_to(work.pristine)
        if not dst.exists() or dst.read_bytes() != f.read_bytes() or dst.stat().st_mtime_ns != f.stat().st_mtime_ns:
            shutil.copy2(f, dst)


# ---------------------------------------------------------------------------------------------
# Tests


def _compiled_stage(module: str) -> list[str]:
    """The module's compiled tests, less those its interpreter stage has run already (the same
    code: compiled, they would pass again), but for the first of them, run again compiled: a
    mutant Numba cannot type fails there."""
    if module not in UNCOMPILED:
        return MODULES[module]
    done = UNCOMPILED[module]
    return [done[0]] + [t for t in MODULES[module] if t not in done]


def _pytest_args(work: Work, module: str, extra: list[str] | None = None, mapping=None) -> list[str]:
    # An entry is a test file or one test of it ("file.py::test_name"); a file the copy lacks
    # (mapped after the copy was made) is left out.
    names = mapping[module] if mapping else _compiled_stage(module)
    files = extra or [str(work.tree / "tests" / t) for t in names
                      if (work.tree / "tests" / t.split("::")[0]).is_file()]
    return [sys.executable, "-m", "pytest", "-x", "-q", "--no-header", "-o", "addopts=", "-p", "no:cacheprovider",
            "-p", GUARD_PLUGIN, *files]


def _interpreted(env: dict) -> dict:
    return dict(env, NUMBA_DISABLE_JIT="1")


def _interpreter_stage(work: Work, module: str, cache: Path) -> tuple[list[str], dict] | None:
    """(pytest command, environment) of the module's interpreter stage, or None if it has none."""
    if module not in UNCOMPILED:
        return None
    return _pytest_args(work, module, mapping=UNCOMPILED), _interpreted(work.env(cache))


def run_tests(work: Work, module: str, cache: Path, extra: list[str] | None = None, quiet=False,
              stage_times: list | None = None) -> tuple[int, float]:
    """Both stages (the interpreter's, if the module has one, then the compiled tests), as a
    mutant runs them: (pytest's exit code, seconds). ``stage_times`` receives each stage's seconds."""
    t0 = time.monotonic()
    first = None if extra else _interpreter_stage(work, module, cache)
    stages = ([first] if first else []) + [(_pytest_args(work, module, extra), work.env(cache))]
    for args, env in stages:
        t_stage = time.monotonic()
        proc = subprocess.run(args, cwd=work.tree, env=env, capture_output=quiet, text=True)
        if stage_times is not None:
            stage_times.append(time.monotonic() - t_stage)
        if proc.returncode:
            if quiet:
                print(proc.stdout[-3000:], proc.stderr[-3000:])
            break
    return proc.returncode, time.monotonic() - t0


def interpreter_coverage(module: str) -> int:
    """Which lines of ``module`` its interpreter stage never runs (coverage.py, on the
    repository's own source, NUMBA_DISABLE_JIT=1 so that the @njit code runs as Python). A
    surviving mutant on such a line is not reached by those tests: it needs a new case, not a
    reason. Returns coverage's exit code."""
    if module not in UNCOMPILED:
        raise SystemExit(f"{module} has no interpreter stage (UNCOMPILED)")
    target = REPO / "src" / "rocking" / module
    with tempfile.TemporaryDirectory() as tmp:
        data = str(Path(tmp) / "coverage.data")
        files = [str(REPO / "tests" / t) for t in UNCOMPILED[module]]
        env = _interpreted(dict(os.environ, NUMBA_NUM_THREADS="1"))
        code = subprocess.run([sys.executable, "-m", "coverage", "run", f"--data-file={data}", f"--include={target}",
                               "-m", "pytest", "-q", "-o", "addopts=", "-p", "no:cacheprovider", *files],
                              cwd=REPO, env=env).returncode
        if code:
            print(f"the interpreter stage's tests fail on the repository (exit {code})")
            return code
        return subprocess.run([sys.executable, "-m", "coverage", "report", "-m", f"--data-file={data}"],
                              cwd=REPO).returncode


def _diff_body(lines) -> tuple[str, ...]:
    # a mutant's diff without its file names, which name the folder it ran in
    return tuple(line for line in lines if not line.startswith(("---", "+++")))


def _mutant_diff(work: Work, module: str) -> tuple[str, ...]:
    """The mutant now written over the copy's module, as cosmic-ray's diff records it."""
    original = (work.pristine / "rocking" / module).read_text(encoding="utf-8")
    mutated = (work.tree / "src" / "rocking" / module).read_text(encoding="utf-8")
    return _diff_body(difflib.unified_diff(original.split("\n"), mutated.split("\n"), lineterm=""))


def shared_folders(work: Work) -> list[Work]:
    path = work.root / SHARE_FILE
    return [Work(Path(f)) for f in path.read_text().split()] if path.exists() else []


def _outcome_elsewhere(work: Work, module: str) -> tuple[Path, object] | None:
    """A sibling folder's result for the mutant now in the copy, if it ran it on the same source."""
    mine = _mutant_diff(work, module)
    original = (work.pristine / "rocking" / module).read_bytes()
    for other in shared_folders(work):
        if not other.db(module).exists() or (other.pristine / "rocking" / module).read_bytes() != original:
            continue
        _, done = _results(other, module)
        for result in done.values():
            if result.diff and result.worker_outcome == "normal" and _diff_body(result.diff.splitlines()[1:]) == mine:
                return other.root, result
    return None


def worker_test(work: Work, module: str) -> int:
    """The per-mutant test command cosmic-ray runs (in its own process group, killed on timeout)."""
    (work.root / "current-test.pid").write_text(str(os.getpid()))
    found = _outcome_elsewhere(work, module)
    if found is not None:
        # Two workers draw from the same mutants in random order; a mutant the other folder has
        # already run on the same source is not run again. Its outcome is copied and the copy says so.
        folder, result = found
        timeout = " (timeout)" if result.output == "timeout" else ""
        print(f"{MIRRORED} {folder}: {result.test_outcome}{timeout}")
        return 0 if result.test_outcome == "survived" else 1
    first = _interpreter_stage(work, module, work.worker_cache)
    mapping = None
    if first:
        meta = json.loads(work.meta(module).read_text()) if work.meta(module).exists() else {}
        limit = meta.get("interpreter_limit_s", INTERPRETER_DEFAULT_S)
        code = _run_limited(*first, work.tree, limit)
        if code is None:
            # Cut off, the stage did not run all its tests: the compiled stage must run them all,
            # not only those the stage leaves out (a mutant that loops for ever in one of them was
            # let through as a survivor until 2026-12-02).
            print(f"{INTERPRETER_CUT} {limit:.0f} s: on to all the compiled tests", flush=True)
            mapping = MODULES
        elif code:
            print(INTERPRETED)
            return code
    _fill_cache(work.base_cache, work.worker_cache, work.tree / "src", stale_modules(work.tree / "src", module))
    return subprocess.run(_pytest_args(work, module, mapping=mapping), cwd=work.tree,
                          env=work.env(work.worker_cache)).returncode


def _run_limited(args: list[str], env: dict, cwd: Path, limit: float) -> int | None:
    """Run a command in a process group of its own; its exit code, or None (the whole group
    killed) if it runs longer than ``limit`` seconds."""
    proc = subprocess.Popen(args, cwd=cwd, env=env, start_new_session=True)
    try:
        return proc.wait(timeout=limit)
    except subprocess.TimeoutExpired:
        os.killpg(proc.pid, signal.SIGKILL)
        proc.wait()
        return None


def baseline(work: Work, module: str) -> dict:
    """Warm the shared cache on the unmutated copy, then time one unmutated run in the per-mutant
    conditions (stale entries dropped): that time sets the timeout."""
    code, warm = run_tests(work, module, work.base_cache, quiet=True)
    if code:
        raise SystemExit(f"{module}: the tests fail on the unmutated copy (exit {code}); fix that first")
    stale = sorted(stale_modules(work.tree / "src", module))
    _fill_cache(work.base_cache, work.worker_cache, work.tree / "src", set(stale))
    stage_times = []
    code, cold = run_tests(work, module, work.worker_cache, quiet=True, stage_times=stage_times)
    if code:
        raise SystemExit(f"{module}: the tests fail with a fresh cache (exit {code})")
    meta = {"warm_s": round(warm, 1), "per_mutant_s": round(cold, 1), "recompiled": stale,
            # A survivor runs every mapped test; when other processes share the CPU it takes 2-3
            # times the unloaded time, and a timeout counts as killed: keep a wide margin.
            "timeout_s": round(max(120.0, 5.0 * cold))}
    if module in UNCOMPILED:
        meta["interpreter_s"] = round(stage_times[0], 1)
        meta["interpreter_limit_s"] = round(max(INTERPRETER_MIN_S, INTERPRETER_FACTOR * stage_times[0]))
    work.meta(module).write_text(json.dumps(meta, indent=1))
    return meta


def changed_lines(work: Work, module: str, since: str) -> set[int]:
    """Line numbers (1-based) of the copy's ``module`` that are new or changed since the commit
    ``since`` (difflib against ``git show since:path``): where a fix's own mutants live."""
    import difflib

    rel = f"src/rocking/{module}"
    old = subprocess.run(["git", "-C", str(REPO), "show", f"{since}:{rel}"], capture_output=True, text=True)
    if old.returncode:
        raise SystemExit(f"--since {since}: {old.stderr.strip()}")
    new = (work.tree / rel).read_text(encoding="utf-8").splitlines()
    out: set[int] = set()
    for tag, _, _, j1, j2 in difflib.SequenceMatcher(None, old.stdout.splitlines(), new, autojunk=False).get_opcodes():
        if tag in ("replace", "insert"):
            out.update(range(j1 + 1, j2 + 1))
    return out


def parse_lines(spec: str) -> set[int]:
    """'12-40,57' → {12, …, 40, 57}."""
    out: set[int] = set()
    for part in filter(None, (p.strip() for p in spec.split(","))):
        lo, _, hi = part.partition("-")
        try:
            a, b = int(lo), int(hi or lo)
        except ValueError:
            raise SystemExit(f"--lines: {part!r} is not a line or a range like 12-40") from None
        out.update(range(a, b + 1))
    return out


def init_session(work: Work, module: str, timeout: float, only: set[int] | None = None) -> None:
    from cosmic_ray.plugins import operator_names

    exclude = sorted(f"{re.escape(n)}$" for n in operator_names() if n not in KEEP_OPERATORS)
    # The test command runs a copy of this script: editing bench/mutation.py during a session
    # must not change (or, half-written, break) the command between two mutants.
    script = work.root / "mutation.py"
    shutil.copy2(Path(__file__).resolve(), script)
    command = f"{sys.executable} {script} --work {work.root} _test {module}"
    config = {
        "cosmic-ray": {
            "module-path": str(work.tree / "src" / "rocking" / module),
            "timeout": timeout,
            "excluded-modules": [],
            "test-command": command,
            "distributor": {"name": "local"},
            "filters": {"operators-filter": {"exclude-operators": exclude}},
        }
    }
    import toml

    work.config(module).write_text(toml.dumps(config))
    bindir = Path(sys.executable).parent
    subprocess.run([bindir / "cosmic-ray", "init", work.config(module), work.db(module)], check=True, cwd=work.tree)
    subprocess.run([bindir / "cr-filter-operators", work.db(module), work.config(module)], check=True, cwd=work.tree)
    from cosmic_ray.work_db import WorkDB, use_db
    from cosmic_ray.work_item import WorkerOutcome, WorkResult

    lines = (work.tree / "src" / "rocking" / module).read_text(encoding="utf-8").splitlines()
    with use_db(str(work.db(module)), WorkDB.Mode.open) as db:
        for item in db.pending_work_items:
            m = item.mutations[0]
            if not _kept(m, lines[m.start_pos[0] - 1]):
                db.set_result(item.job_id, WorkResult(output="not in the policy", worker_outcome=WorkerOutcome.SKIPPED))
            elif only is not None and m.start_pos[0] not in only:
                db.set_result(item.job_id, WorkResult(output="outside --lines/--since",
                                                      worker_outcome=WorkerOutcome.SKIPPED))


def execute(work: Work, module: str, deadline: float | None) -> bool:
    """Run the pending mutants of one session; True when it finished, False when stopped at the deadline."""
    bindir = Path(sys.executable).parent
    proc = subprocess.Popen([bindir / "cosmic-ray", "exec", work.config(module), work.db(module)], cwd=work.tree)
    # Stopped by Ctrl-C or `kill PID` alike (a background job starts with SIGINT ignored).
    signal.signal(signal.SIGINT, signal.default_int_handler)
    signal.signal(signal.SIGTERM, signal.default_int_handler)
    try:
        while proc.poll() is None:
            if deadline is not None and time.time() > deadline:
                _stop(work, proc)
                return False
            time.sleep(2)
    except KeyboardInterrupt:
        _stop(work, proc)
        raise
    finally:
        restore(work)
    return proc.returncode == 0


def _stop(work: Work, proc: subprocess.Popen) -> None:
    # The mutant being tested gets no result and stays pending; `restore` (in execute's finally)
    # puts the module back. The test command runs in a session of its own, whose group id is the
    # pid it wrote down.
    proc.terminate()
    try:
        proc.wait(timeout=30)
    except subprocess.TimeoutExpired:
        proc.kill()
        proc.wait()
    try:
        pgid = int((work.root / "current-test.pid").read_text())
        # only if that pid is still our test command (a finished one's pid may have been reused)
        if b"_test" in Path(f"/proc/{pgid}/cmdline").read_bytes():
            os.killpg(pgid, signal.SIGKILL)
    except (OSError, ValueError):
        pass


# ---------------------------------------------------------------------------------------------
# Results


def _results(work: Work, module: str):
    from cosmic_ray.work_db import WorkDB, use_db

    with use_db(str(work.db(module)), WorkDB.Mode.open) as db:
        done = {job: result for job, result in db.results}
        items = list(db.work_items)
    return items, done


def summarise(work: Work, module: str) -> dict:
    items, done = _results(work, module)
    counts = dict(mutants=0, killed=0, timeout=0, survived=0, incompetent=0, pending=0)
    for item in items:
        result = done.get(item.job_id)
        if result is not None and result.worker_outcome == "skipped":
            continue
        counts["mutants"] += 1
        if result is None:
            counts["pending"] += 1
        elif result.test_outcome == "survived":
            counts["survived"] += 1
        elif result.test_outcome == "killed":
            counts["timeout" if result.output == "timeout" else "killed"] += 1
        else:
            counts["incompetent"] += 1
    return counts


def union_counts(works: list[Work], module: str) -> dict:
    """Counts over several folders on the same source, each mutant once (told apart by its diff):
    run in any of them, its own outcome rather than a copied one."""
    total = summarise(works[0], module)["mutants"]
    outcome: dict[tuple[str, ...], str] = {}
    for w in works:
        if not w.db(module).exists():
            continue
        for result in _results(w, module)[1].values():
            if result.worker_outcome != "normal" or not result.diff:
                continue
            key = _diff_body(result.diff.splitlines()[1:])
            if key in outcome and (result.output or "").startswith(MIRRORED):
                continue
            outcome[key] = "timeout" if result.output == "timeout" else str(result.test_outcome.value)
    counts = dict(mutants=total, killed=0, timeout=0, survived=0)
    for value in outcome.values():
        counts[value] = counts.get(value, 0) + 1
    counts["pending"] = total - len(outcome)
    return counts


def survivors(work: Work, module: str):
    items, done = _results(work, module)
    for item in items:
        result = done.get(item.job_id)
        # a copied outcome is listed by the folder that ran it
        if result is not None and result.test_outcome == "survived" and not (result.output or "").startswith(MIRRORED):
            yield item, result


def describe(item) -> str:
    m = item.mutations[0]
    operator = m.operator_name.removeprefix("core/")
    return f"{item.job_id[:8]}  {m.module_path.name}:{m.start_pos[0]}  {operator}#{m.occurrence}"


def find_item(work: Work, job: str):
    for module in MODULES:
        if work.db(module).exists():
            items, _ = _results(work, module)
            for item in items:
                if item.job_id.startswith(job):
                    return module, item
    raise SystemExit(f"no mutant {job} in {work.sessions}")


def try_mutant(work: Work, job: str, tests: list[str], current: bool = False, interpreter: bool = False) -> int:
    """Apply one mutant and run the given tests (taken from the repository, where a new test is
    written) in a throw-away copy of the copy, with an empty numba cache: a session may be
    running in the main copy meanwhile. Returns pytest's exit code (0: the mutant survives).

    ``current``: apply it to the repository's source as it is now instead of the copy's (to
    re-check a survivor after a fix elsewhere, without dropping the sessions). If the mutated
    module itself has changed since the copy, the mutant's position may be wrong: it is then
    placed by its text instead (the one line it changes must occur exactly once in today's
    module), or refused.

    ``interpreter``: run the tests with NUMBA_DISABLE_JIT=1 (the interpreter stage of UNCOMPILED)."""
    from cosmic_ray.mutating import apply_mutation
    from cosmic_ray.plugins import get_operator

    module, item = find_item(work, job)
    tree, cache = work.root / "try-tree", work.root / "numba-try"
    for p in (tree, cache):
        shutil.rmtree(p, ignore_errors=True)
    by_text = None
    if current:
        relative = Path("rocking") / module
        if (REPO / "src" / relative).read_bytes() != (work.pristine / relative).read_bytes():
            by_text = _mutated_line(work, item, relative)
        shutil.copytree(REPO / "src", tree / "src", ignore=shutil.ignore_patterns("__pycache__"))
    else:
        shutil.copytree(work.pristine, tree / "src")
    origin = REPO if current else work.tree  # where the tests (and their helpers) come from
    shutil.copytree(origin / "tests", tree / "tests", ignore=shutil.ignore_patterns("__pycache__"))
    shutil.copy2(origin / "pyproject.toml", tree)
    args = []
    for t in tests:
        file_part, _, node = t.partition("::")
        src = (REPO / file_part).resolve()
        dst = tree / src.relative_to(REPO)
        shutil.copy2(src, dst)
        args.append(str(dst) + (f"::{node}" if node else ""))
    m = item.mutations[0]
    target = tree / "src" / Path(m.module_path).relative_to(work.tree / "src")
    if by_text is not None:
        before, after = by_text
        target.write_text(target.read_text().replace(before, after))
    else:
        _, code = apply_mutation(target, get_operator(m.operator_name)(**(m.operator_args or {})), m.occurrence)
        if code is None:
            raise SystemExit("mutation could not be applied (has the module changed since the session began?)")
    print(describe(item), flush=True)
    cmd = _pytest_args(work, module, args)
    env = work.env(cache, tree)
    code = subprocess.run(cmd, cwd=tree, env=_interpreted(env) if interpreter else env).returncode
    print("survives" if code == 0 else f"killed (pytest exit {code})")
    return code


def _mutated_line(work: Work, item, relative: Path) -> tuple[str, str]:
    """(line before, line after) of a mutant that changes one line of the copy's module, if
    that line occurs exactly once in the repository's current module; else refuse."""
    from cosmic_ray.mutating import apply_mutation
    from cosmic_ray.plugins import get_operator

    m = item.mutations[0]
    with tempfile.TemporaryDirectory() as scratch:
        copy = Path(scratch) / relative.name
        shutil.copy2(work.pristine / relative, copy)
        apply_mutation(copy, get_operator(m.operator_name)(**(m.operator_args or {})), m.occurrence)
        old = (work.pristine / relative).read_text().splitlines(keepends=True)
        new = copy.read_text().splitlines(keepends=True)
    changed = [(a, b) for a, b in zip(old, new) if a != b]
    current = (REPO / "src" / relative).read_text()
    if len(old) != len(new) or len(changed) != 1 or current.count(changed[0][0]) != 1:
        raise SystemExit(f"{relative} has changed since the copy, and this mutant's line cannot be found "
                         "in it unambiguously: it cannot be placed on the current source")
    return changed[0]


def _kept(mutation, line: str) -> bool:
    """The mutant policy, besides the operator list: one number mutant per literal (occurrences
    2k and 2k+1 are n+1 and n-1 of the k-th number: whether a constant is tested at all is the
    question, and a mutant of a compiled module costs a recompilation), and no flag of numba's
    decorator (cache=, _nrt=: they change when and how code compiles, never what it computes)."""
    if mutation.operator_name not in KEEP_OPERATORS:
        return False
    if mutation.operator_name == "core/NumberReplacer" and mutation.occurrence % 2:
        return False
    return not (line.lstrip().startswith("@njit") and mutation.operator_name in
                ("core/ReplaceTrueWithFalse", "core/ReplaceFalseWithTrue"))


def plan(work: Work, modules: list[str]) -> None:
    """How many mutants each module has under the policy, and roughly how long it takes, from the
    per-mutant time of a finished baseline or, without one, 45 s for a module that recompiles the
    solver core or the stack engine (each ~40 s to compile, unloaded) and 10 s otherwise (the
    2-CPU development machine)."""
    from cosmic_ray.commands.init import _all_work_items

    print("| module | mutants | recompiles | estimate |")
    print("|---|---|---|---|")
    total = 0.0
    for module in modules:
        path = REPO / "src" / "rocking" / module
        lines = path.read_text(encoding="utf-8").splitlines()
        n = sum(1 for item in _all_work_items([path], {})
                if _kept(item.mutations[0], lines[item.mutations[0].start_pos[0] - 1]))
        stale = stale_modules(REPO / "src", module)
        meta = json.loads(work.meta(module).read_text()) if work.meta(module).exists() else {}
        slow = stale & {"solver/compiled.py", "stack/engine.py"}
        per = meta.get("per_mutant_s", 45.0 if slow else 10.0)
        total += n * per
        print(f"| {module} | {n} | {', '.join(sorted(stale)) or '-'} | {n * per / 60:.0f} min |")
    print(f"total ≈ {total / 3600:.1f} h on one worker")


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--work", type=Path, default=DEFAULT_WORK, help=f"work folder (default {DEFAULT_WORK})")
    sub = parser.add_subparsers(dest="cmd", required=True)
    p = sub.add_parser("prepare", help="copy the repository into the work folder")
    p.add_argument("--force", action="store_true", help="copy again, dropping every session")
    p = sub.add_parser("run", help="run (or resume) the sessions of the given modules, in order")
    p.add_argument("modules", nargs="*", help=f"paths under src/rocking (default: all of {', '.join(MODULES)})")
    p.add_argument("--minutes", type=float, help="stop after this long (the interrupted mutant stays pending)")
    p.add_argument("--timeout", type=float, help="seconds per mutant, also for sessions already begun "
                   "(default: 5 × the baseline's per-mutant time, at least 120)")
    p.add_argument("--share", type=Path, action="append", default=[], metavar="FOLDER",
                   help="another work folder on the same source: a mutant it has run is not run "
                        "again here, its outcome is copied (give it to both workers, each naming the other)")
    p.add_argument("--since", metavar="COMMIT",
                   help="when a session begins: only the mutants on lines new or changed since COMMIT (a fix's own lines)")
    p.add_argument("--lines", metavar="SPEC", help="when a session begins: only the mutants on these lines, e.g. 12-40,57")
    sub.add_parser("report", help="counts per module")
    sub.add_parser("union", help="counts of distinct mutants over this folder and those it shares with (`run --share`)")
    p = sub.add_parser("plan", help="mutants per module under the policy, and a time estimate (runs nothing)")
    p.add_argument("modules", nargs="*")
    p = sub.add_parser("survivors", help="list surviving mutants with their diffs")
    p.add_argument("modules", nargs="*")
    p = sub.add_parser("show", help="the diff and test output of one mutant")
    p.add_argument("job")
    p = sub.add_parser("try", help="apply one mutant in the copy and run the given tests on it")
    p.add_argument("job")
    p.add_argument("tests", nargs="+", help="test files or node ids, relative to the repository")
    p.add_argument("--current", action="store_true",
                   help="mutate the repository's current source, not the copy's (a changed module: placed by the line's text)")
    p.add_argument("--interpreter", action="store_true", help="run the tests uncompiled (NUMBA_DISABLE_JIT=1)")
    p = sub.add_parser("coverage", help="lines of MODULE its interpreter stage never runs (coverage.py)")
    p.add_argument("module")
    p = sub.add_parser("deps", help="which compiled modules a mutant of MODULE recompiles")
    p.add_argument("module")
    p = sub.add_parser("_test", help=argparse.SUPPRESS)
    p.add_argument("module")
    args = parser.parse_args(argv)
    work = Work(args.work.resolve())

    if args.cmd == "_test":
        return worker_test(work, args.module)
    if args.cmd == "prepare":
        prepare(work, args.force)
        return 0
    if args.cmd == "plan":
        plan(work, args.modules or list(MODULES))
        return 0
    if args.cmd == "coverage":
        return interpreter_coverage(args.module)
    if args.cmd == "deps":
        print(sorted(stale_modules(REPO / "src", args.module)))
        return 0
    if args.cmd == "run":
        modules = args.modules or list(MODULES)
        unknown = [m for m in modules if m not in MODULES]
        if unknown:
            raise SystemExit(f"no test mapping for {unknown}; add them to MODULES")
        deadline = time.time() + 60 * args.minutes if args.minutes else None
        prepare(work, force=False)
        if args.share:
            (work.root / SHARE_FILE).write_text("\n".join(str(f.resolve()) for f in args.share) + "\n")
        for module in modules:
            if not work.db(module).exists():
                meta = baseline(work, module)
                print(f"{module}: baseline {meta}", flush=True)
                only = None
                if args.since:
                    only = changed_lines(work, module, args.since)
                if args.lines:
                    only = parse_lines(args.lines) if only is None else only & parse_lines(args.lines)
                if only is not None:
                    print(f"{module}: only the mutants on {len(only)} lines", flush=True)
                init_session(work, module, args.timeout or meta["timeout_s"], only)
            else:  # re-warm the shared cache (and check the unmutated tests still pass)
                if run_tests(work, module, work.base_cache, quiet=True)[0]:
                    raise SystemExit(f"{module}: the tests fail on the unmutated copy")
                if args.timeout:
                    config = work.config(module).read_text()
                    config = re.sub(r"(?m)^timeout = .*$", f"timeout = {args.timeout}", config)
                    work.config(module).write_text(config)
            counts = summarise(work, module)
            print(f"{module}: {counts['pending']} of {counts['mutants']} mutants to run", flush=True)
            if not execute(work, module, deadline):
                print("stopped at the deadline; `run` again to resume")
                break
            print(f"{module}: {summarise(work, module)}", flush=True)
        return 0
    if args.cmd == "report":
        print("| module | mutants | killed | timeout | survived | incompetent | pending | per mutant |")
        print("|---|---|---|---|---|---|---|---|")
        for module in MODULES:
            if work.db(module).exists():
                c = summarise(work, module)
                meta = json.loads(work.meta(module).read_text()) if work.meta(module).exists() else {}
                print(f"| {module} | {c['mutants']} | {c['killed']} | {c['timeout']} | {c['survived']} | "
                      f"{c['incompetent']} | {c['pending']} | {meta.get('per_mutant_s', '?')} s |")
        return 0
    if args.cmd == "union":
        print(f"distinct mutants over {work.root} and {', '.join(str(w.root) for w in shared_folders(work)) or '(none shared)'}")
        for module in MODULES:
            if work.db(module).exists():
                print(f"{module}: {union_counts([work, *shared_folders(work)], module)}")
        return 0
    if args.cmd == "survivors":
        for module in args.modules or list(MODULES):
            if work.db(module).exists():
                for item, result in survivors(work, module):
                    print(describe(item))
                    print("\n".join(line for line in (result.diff or "").splitlines() if line[:1] in "+-"
                                    and line[:3] not in ("+++", "---")))
        return 0
    if args.cmd == "show":
        module, item = find_item(work, args.job)
        _, done = _results(work, module)
        result = done.get(item.job_id)
        print(describe(item))
        print(result.diff if result else "(not run yet)")
        if result:
            print(result.test_outcome, (result.output or "")[-2000:])
        return 0
    if args.cmd == "try":
        return 1 if try_mutant(work, args.job, args.tests, args.current, args.interpreter) == 0 else 0
    return 2


if __name__ == "__main__":
    sys.exit(main())
