"""Stage 1 of the pipeline: problem file (YAML) -> validated `Problem`."""
