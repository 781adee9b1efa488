"""Exam papers and answers templates (papers.md): what a student receives.

`keys.py` the graded keys of a question and the shape of each answer, known before solving;
`template.py` answers.yaml; `paper.py` paper.md; `html.py` paper.html and papers.html;
`workflow.py` the files of `robosolve paper` and of every variant.
"""
