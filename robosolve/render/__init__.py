"""Stage 4: Markdown, JSON and figures from answers. Renderers never compute physics."""
