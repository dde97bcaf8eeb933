"""Guided lessons for teaching: lesson files (assets/lessons/*.toml, docs/lessons.md), the values
their texts quote, the results they show (shipped or cached), and the Lessons panel.

``format`` reads and checks lesson files; ``values`` computes the quotable numbers of a result;
``text`` fills the templates; ``results`` finds or solves a lesson's results. None of these imports
trame or VTK.
"""
