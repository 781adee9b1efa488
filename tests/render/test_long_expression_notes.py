"""A report's "(long: …; see results.json)" points only to what results.json holds.

results.json's `equations_of_motion` keeps the energies, the equations, M, c and g (spec row);
the report's other steps (⁰J, ⁰L, ⁰W, Φ, 𝓛, ∂𝓛/∂q̇) are the report's alone, so their notes say
only how long they are. Read from the bundled problems' golden reports (robosolve's own output,
checked here against the spec's list of keys)."""
import re
from pathlib import Path

GOLDEN = Path(__file__).resolve().parents[1] / "golden"
# The left sides whose values results.json holds: T_b, U_b, a joint's equation, M, c, g.
HELD = re.compile(r"^(T_\{|U_\{|\\text\{joint \d+ |M\(q\)|c\(q, \\dot q\)|g\(q\))")
NOTE = re.compile(r"^(.*?)\s*=\s*\\text\{\(long: \d+ (operations|terms)(; see results\.json)?\)\}")


def _notes():
    for report in sorted(GOLDEN.glob("*/report.md")):
        for line in report.read_text(encoding="utf-8").splitlines():
            found = NOTE.match(line)
            if found:
                yield report.parent.name, found.group(1), bool(found.group(3))


def test_only_what_results_json_holds_is_pointed_to():
    notes = list(_notes())
    assert any(pointed for *_, pointed in notes) and any(not p for *_, p in notes)
    for problem, lhs, pointed in notes:
        assert pointed == bool(HELD.match(lhs)), (problem, lhs)
