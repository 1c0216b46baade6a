"""lazyground: act on ambiguous requests by grounding them lazily inside a motion planner.

Implements Hernández, Moll and Kavraki, "Lazy Evaluation of Goal Specifications
Guided by Motion Planning" (ICRA 2019). This package's top level imports no
pydrake; Drake lives in :mod:`lazyground.drake` and :mod:`lazyground.viz`.
"""

__version__ = "0.1.0"
