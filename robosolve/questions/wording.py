"""What the types' paper statements share (papers.md): a statement asks for exactly what the
student hands in, the question's graded keys (its `grade` list, else its type's principal
keys), each in the course's words.

Not a question type (the registry lists its type modules by name, and this is not one of them).
A type's statement words its keys (`words`: dotted key -> phrase); `asked` gives the phrases of
the graded ones, in grading order, through `say.asked(question)` (papers/paper.py `Say`).
"""

from __future__ import annotations

__all__ = ["asked", "listing", "sentence"]


def asked(q, say, words: dict) -> list[str]:
    """The phrases of the question's graded keys, in order; a field graded alone
    ("energy.end") without its own phrase takes its record's."""
    out = []
    for key in say.asked(q):
        phrase = words.get(key)
        if phrase is None:
            phrase = words.get(key.partition(".")[0])
        if phrase and phrase not in out:
            out.append(phrase)
    return out


def listing(phrases) -> str:
    """'a', 'a and b', 'a, b and c' ('a; b; and c' when a phrase has commas of its own)."""
    phrases = list(phrases)
    if len(phrases) <= 1:
        return "".join(phrases)
    if any(", " in p for p in phrases):
        return "; ".join(phrases[:-1]) + "; and " + phrases[-1]
    return ", ".join(phrases[:-1]) + " and " + phrases[-1]


def sentence(text: str) -> str:
    """A statement's text with its first letter capitalised."""
    return text[:1].upper() + text[1:]
