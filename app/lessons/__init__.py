"""Guided lessons for teaching (docs/lessons.md): lesson files in assets/lessons/, the values their
texts quote, the results they show (shipped or cached), the Lessons panel and presenter mode.

``format`` reads and checks lesson files; ``claims`` binds each sentence to the conditions that
make it true and evaluates them; ``values`` computes the quotable numbers of a result; ``text``
fills the templates; ``results`` finds or solves a lesson's results (none of these five imports
trame or VTK); ``panel`` is the session component (state and handlers); ``widgets`` the
page's Lessons card, presenter-mode style sheet and key handler.
"""
