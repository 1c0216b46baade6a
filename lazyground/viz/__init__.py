"""Seeing a planned grounding: top-down parking plots, Meshcat (live and HTML replay), the demo.

Never imported by the planner. ``style`` and ``trace`` are plain numpy;
``plots`` uses matplotlib; ``meshcat_view`` uses pydrake.
"""
