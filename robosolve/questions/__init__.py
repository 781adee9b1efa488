"""The question types: one registry (`registry.QUESTION_TYPES`) that the loader,
the solvers' dispatch, the renderers and the grader all read."""

from robosolve.questions.registry import COMMON_KEYS, QUESTION_TYPES, AnswerKey, QuestionType, question_type, title

__all__ = ["COMMON_KEYS", "QUESTION_TYPES", "AnswerKey", "QuestionType", "question_type", "title"]
