"""Rule-based grounding: a text request → every valid interpretation → goal regions.

Pure Python (no pydrake). ``ground(request, scene)`` is the entry point; the
words live in ``lexicon.yaml`` (extend it, or set $LAZYGROUND_LEXICON), the
grammar in ``grammar.lark`` (its meanings in ``parse.py``, the parse's data
model in ``phrases.py``), the goal-region definitions per type in
``lazyground/scene/types.yaml``. The request language is documented in
docs/requests.md.
"""

from grounding.model import ACTIONS, Grounding, GroundingError, Interpretation
from grounding.lexicon import Lexicon, load_lexicon
from grounding.ground import ground

__all__ = ["ACTIONS", "Grounding", "GroundingError", "Interpretation", "Lexicon", "ground", "load_lexicon"]
