"""`robosolve variants`: draw the variants, write their problem files, solve them.

Everything that can fail on input (the problem, the roster, `require`, too few distinct
variants, a variant that does not load) fails before anything is written; the outputs are
written into a staging folder beside DIR that replaces DIR at the end (DIR is an output
folder, problem-format.md §2), so an error or an interrupt leaves DIR as it was.

Each variant's solution is computed from the very text written to its problem.yaml, so
`robosolve solve DIR/<name>-<id>/problem.yaml` gives the same report and results.
"""

from __future__ import annotations

import csv
import io
from dataclasses import dataclass, field
from pathlib import Path

import yaml

from robosolve.errors import ExitStatus, InputError, InputIssue
from robosolve.run.execution import make_task, run_tasks
from robosolve.core.printing import sstr
from robosolve.load.expressions import DECIMAL_ADVICE, SHORT_NUMBER_CHARS
from robosolve.render.numbers import prose_number

# what a variants folder holds, for the working directory written in place (robosolve.run.outputs)
OWN_FILES = ("variants.csv", "roster.csv", "*/problem.yaml", "*/report.md", "*/report.html",
             "*/report.ipynb", "*/results.json", "*/figures/*.png", "*/paper.md", "*/paper.html",
             "*/answers.yaml", "papers.html")


@dataclass
class Variant:
    id: str                       # the folder's id: 001 or jo-smith
    student: str                  # the roster's id as written ('' with --count)
    values: dict                  # parameter name -> exact sympy value
    folder: str = ""              # <name>-<id>
    text: str = ""                # its problem.yaml


@dataclass
class Plan:
    problem: object
    spec: object
    seed: int
    variants: list = field(default_factory=list)
    roster: bytes = b""           # DIR/roster.csv (with --roster)


# ---------------------------------------------------------------------------
# problem.yaml of a variant

class _Dumper(yaml.SafeDumper):
    """Block style for the structure, flow style for leaf lists and mappings, `|` for text."""


def _str(dumper, value):
    style = "|" if "\n" in value else None
    return dumper.represent_scalar("tag:yaml.org,2002:str", value, style=style)


_Dumper.add_representer(str, _str)


def dump_problem(data: dict) -> str:
    return yaml.dump(data, Dumper=_Dumper, sort_keys=False, allow_unicode=True,
                     default_flow_style=None, width=100)


def yaml_value(value):
    """An exact value for a problem file: a YAML integer, else an expression string."""
    import sympy as sp

    if isinstance(value, sp.Integer):
        return int(value)
    return sstr(value)


def variant_data(data: dict, name: str, values: dict) -> dict:
    out = {k: v for k, v in data.items() if k != "variants"}
    out["name"] = name
    params = dict(out.get("parameters") or {})
    for k, v in values.items():
        params[k] = yaml_value(v) if v is not None else None
    out["parameters"] = params
    return out


# ---------------------------------------------------------------------------
# planning: load, name, check, draw (nothing written)

def load_source(path: Path):
    from robosolve.load.loader import load_problem_text
    from robosolve.load.yamlsource import parse_yaml, read_text_file

    file = str(path)
    text = read_text_file(path, line=1)
    problem = load_problem_text(text, file)
    if problem.variants is None:
        raise InputError([InputIssue(file, 1, "", "no `variants` section: nothing to vary "
                                     "(see docs/variants.md)")])
    source, _ = parse_yaml(text, file)
    return problem, source.data


def template_problem(data: dict, problem):
    """The problem with every varied parameter null: plain real symbols for the checks."""
    from robosolve.load.loader import load_problem_text

    tdata = variant_data(data, problem.name, {p.name: None for p in problem.variants.parameters})
    return load_problem_text(dump_problem(tdata), problem.file)


MAX_VARIANTS = 100_000         # variants made at once (each holds its problem text in memory)


def too_few(file, spec, n: int, asked: int, what: str):
    what = what.replace("meet", "meets").replace("exist", "exists") if n == 1 else what
    raise InputError([InputIssue(file, spec.line, "variants",
                                 f"only {n} distinct variant{'s' if n != 1 else ''} {what} "
                                 f"({asked} asked)")])


def never_met(file, requirement, asked: int):
    """No variant at all: told at the condition that holds for none of the drawn values."""
    raise InputError([InputIssue(file, requirement.line, requirement.path,
                                 f"only 0 distinct variants meet `require` ({asked} asked): "
                                 f"{requirement.text!r} holds for none of the values the section "
                                 "draws; widen the ranges or relax the condition")])


def check_count(file, spec, asked: int) -> None:
    """Refuse a count that cannot be met before anything is drawn or allocated: more than the
    grid of drawn values holds, or more than MAX_VARIANTS."""
    if asked > spec.grid_size:
        too_few(file, spec, spec.grid_size, asked, "exist")
    if asked > MAX_VARIANTS:
        raise InputError([InputIssue(file, spec.line, "variants",
                                     f"{asked} variants asked: robosolve makes at most "
                                     f"{MAX_VARIANTS} at once")])


def plan_variants(path: Path, ids: list, seed: int, progress=None) -> Plan:
    """ids: [(variant id, student)] in order. Raises InputError (exit 2) on any problem."""
    from robosolve.variants.draw import Drawer, TooFew
    from robosolve.variants.require import RequirementChecker

    problem, data = load_source(path)
    spec = problem.variants
    checker = RequirementChecker(template_problem(data, problem), spec, problem.file)
    counting = ((lambda: progress.task("checking the conditions over the grid", checker.table_work()))
                if progress else None)
    drawer = Drawer(spec, checker, seed, problem.file, counting)
    asked = getattr(ids, "asked", None) or len(ids)      # --count 10**19 has no len()
    check_count(problem.file, spec, asked)
    plan = Plan(problem, spec, seed)
    step = progress.task("drawing", len(ids)) if progress else None
    for vid, student in ids:
        try:
            index = drawer.next()
        except TooFew as exc:       # the grid, counted once the draws ran short, holds no more
            if exc.never:
                never_met(problem.file, exc.never[0], asked)
            too_few(problem.file, spec, exc.count, asked, "meet `require`" if spec.require else "exist")
        values = drawer.values(index)
        v = Variant(vid, student, values, folder=f"{problem.name}-{vid}")
        v.text = dump_problem(variant_data(data, v.folder, values))
        plan.variants.append(v)
        if step:
            step()
    return plan


def variants_csv(plan: Plan) -> bytes:
    import sympy as sp

    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    names = [p.name for p in plan.spec.parameters]
    w.writerow(["variant", "student", "seed"] + names)
    for v in plan.variants:
        w.writerow([v.id, v.student, plan.seed] + [sstr(v.values[n]) for n in names])
    return buf.getvalue().encode("utf-8")


# ---------------------------------------------------------------------------
# running

def run(plan: Plan, out: Path, formats=("md",), solve=True, jobs=0, scheduler=None, progress=None,
        inputs=()):
    """Load (and solve) every variant, then write DIR as one output folder (robosolve.run.outputs).
    Returns (status, results in variant order)."""
    from robosolve.run.outputs import write_output_folder

    tasks = [make_task(v.text, f"{out}/{v.folder}/problem.yaml", formats, solve,
                       paper={"student": v.student, "variant": v.folder}) for v in plan.variants]
    results = [None] * len(tasks)
    files = {"variants.csv": variants_csv(plan)}
    if plan.roster:
        files["roster.csv"] = plan.roster
    step = progress.task("solving" if solve else "checking the variants", len(tasks)) if progress else None
    for i, res in run_tasks(tasks, jobs, scheduler):
        results[i] = res
        v = plan.variants[i]
        files[f"{v.folder}/problem.yaml"] = v.text.encode("utf-8")
        for rel, data in res.files.items():
            files[f"{v.folder}/{rel}"] = data
        res.files = {}            # the bytes are in `files` now
        if step:
            step()
    bad = [(v, r) for v, r in zip(plan.variants, results) if r.status == ExitStatus.INPUT]
    if bad:
        raise VariantInvalid([_invalid_variant_message(plan, bad)])
    if "html" in formats:             # the whole class, one paper per printed page (papers.md)
        from robosolve.papers.workflow import papers_html

        pages = [(v.folder, files[f"{v.folder}/paper.html"]) for v in plan.variants
                 if f"{v.folder}/paper.html" in files]
        files["papers.html"] = papers_html(pages, f"{plan.problem.title or plan.problem.name}: papers")
    write_output_folder(out, dict(sorted(files.items())), inputs=inputs, own=OWN_FILES)
    status = max([r.status for r in results] + [ExitStatus.OK])
    return status, results


def _invalid_variant_message(plan: Plan, bad: list) -> str:
    """One message for the draws that break a rule of the problem, told against the source's
    `variants` section: the variant's own problem.yaml is never written, so its FILE:LINE
    would point nowhere."""
    import re

    import sympy as sp

    variant, result = bad[0]
    drawn = ", ".join(_drawn_text(p.name, variant.values[p.name]) for p in plan.spec.parameters)
    first = result.messages[0] if result.messages else "it does not load"
    where = re.match(r"^.*?problem\.yaml:(\d+): ", first)
    what = first[where.end():] if where else first
    line = _source_line(plan.problem.file, what)
    at = f" (line {line} of {Path(plan.problem.file).name})" if line else ""
    more = f"; {len(bad) - 1} more variant{'s' if len(bad) > 2 else ''} too" if len(bad) > 1 else ""
    if what.endswith("; " + DECIMAL_ADVICE):
        return _too_many_digits(plan, variant, drawn, what[:-len(DECIMAL_ADVICE) - 2], more)
    return (f"{plan.problem.file}:{plan.spec.line}: variants: variant {variant.id} draws {drawn}, "
            f"which is not a valid problem: {what}{at}{more}. Narrow the ranges or add a `require` "
            "condition; nothing was written")


def _source_line(file: str, what: str) -> int | None:
    """The line in the source problem of the entry a variant's message names (`bodies[0].mass:
    …`): the variant's own problem.yaml is dumped from data, never written, so its line numbers
    would point nowhere. None when the message names no entry of the source."""
    import re

    from robosolve.load.yamlsource import parse_yaml, read_text_file

    named = re.match(r"^([A-Za-z_][\w.\[\]-]*): ", what)
    if not named or named.group(1) in ("variants", "parameters"):
        return None
    path = tuple(int(m.group(2)) if m.group(2) else m.group(1)
                 for m in re.finditer(r"([^.\[\]]+)|\[(\d+)\]", named.group(1)))
    try:
        source, _ = parse_yaml(read_text_file(Path(file), line=1), file)
    except Exception:           # the source loaded a moment ago; if it cannot now, say no line
        return None
    return source.lines.get(path[:1]) and source.line(path)


def _too_many_digits(plan: Plan, variant: Variant, drawn: str, what: str, more: str) -> str:
    """A drawn value too long to stay exact: the loader's advice is for a value typed in a
    problem file, but this one was drawn, so the message is told at the varied parameter that
    drew it (the one named, or else the one whose draw has the most digits: a parameter computed
    from it) with advice about its range and step, or its choices."""
    import re

    from robosolve.load.expressions import exact_digits

    named = re.match(r"parameters\.([^:\s]+): ", what)
    source = plan.spec.parameter(named.group(1)) if named else None
    if source is None:
        source = max(plan.spec.parameters, key=lambda p: exact_digits(variant.values[p.name]))
    fix = ("use a coarser step (fewer digits in the step and the range's ends)" if source.kind == "range"
           else "give the choices fewer digits")
    cause = (f"the values drawn from {source.written} are that long" if named and named.group(1) == source.name
             else f"it is computed from {source.name}, whose values drawn from {source.written} have too many digits")
    return (f"{plan.problem.file}:{source.line}: variants.parameters.{source.name}: variant {variant.id} "
            f"draws {drawn}, which is not a valid problem: {what}; {cause}: {fix}{more}; nothing was written")


def _drawn_text(name: str, value) -> str:
    """`L1 = 3/10` as drawn; a value whose exact text is long (a fine step over a wide range) by
    its decimal value: `L1 ≈ 98.1472`, not a 61-character fraction."""
    exact_text = sstr(value)
    if len(exact_text) <= SHORT_NUMBER_CHARS:
        return f"{name} = {exact_text}"
    return f"{name} ≈ {prose_number(float(value))}"


class VariantInvalid(Exception):
    """A drawn variant does not load (its values break a rule of the problem file)."""

    def __init__(self, messages):
        self.messages = messages
        super().__init__("\n".join(messages))


def check_out(out: Path, inputs=()) -> str | None:
    """Why DIR cannot be the output folder (problem-format.md §2), or None. Touches nothing."""
    from robosolve.run.outputs import OutputFolderError, check_output_folder

    try:
        check_output_folder(out, inputs)
    except OutputFolderError as exc:
        return str(exc)
    return None
