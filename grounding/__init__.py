"""Rule-based grounding: a text request → every valid interpretation → goal regions.

Pure Python (no pydrake). ``ground(request, scene)`` is the entry point.
"""

from grounding.model import ACTIONS, Grounding, GroundingError, Interpretation
from grounding.ground import ground

__all__ = ["ACTIONS", "Grounding", "GroundingError", "Interpretation", "ground"]
