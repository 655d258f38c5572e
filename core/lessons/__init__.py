"""Lessons: the lecture told figure by figure, as checked data.

A lesson file (:mod:`core.lessons.lesson_file` reads it; the shipped ones are in
``core/lessons/files``) is a sequence of steps, each naming a scene, the panes
to show and a few sentences of explanation.  What a step's words claim about
the window is written as facts the pipelines decide (:mod:`core.lessons.facts`),
and an exercise is a fact with the answer hidden (:mod:`core.lessons.exercises`);
:mod:`core.lessons.authoring` records the window's state as a new step.
"""
