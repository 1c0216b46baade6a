"""The generated request corpus (tools/request_corpus.py) on a seeded sample: the grounder agrees with the
independent oracle (tools/request_oracle.py) on every request, and grounds at least 95 % of those that name
something. ``python3 -m tools.request_corpus`` runs the whole corpus (> 5,000 requests)."""

from __future__ import annotations

import subprocess
import sys

from tests.unit.test_grounding import REPO
from tools import request_corpus


def test_a_seeded_sample_has_no_wrong_grounding():
    outcomes = request_corpus.run(per_scene=200, generated=20, seed=0, sample=250)
    s = request_corpus.summary(outcomes)
    wrong = [(o.item.text, sorted(o.expected), sorted(o.got)) for o in outcomes if o.verdict == "wrong"]
    assert not wrong, wrong[:5]
    assert s["grounded_share"] >= 0.95, s
    assert s["right"] >= 150  # most of the sample names something


def test_the_full_corpus_is_large_enough():
    names = request_corpus.scenes(generated=20, seed=0)
    assert len(names) >= 30 and 200 * len(names) >= 5000


def test_the_oracle_never_imports_the_grounder():
    code = ("import sys; import tools.request_oracle; "
            "assert not any(m == 'grounding' or m.startswith('grounding.') for m in sys.modules), 'grounding imported'")
    subprocess.run([sys.executable, "-c", code], check=True, cwd=REPO, timeout=60)


def test_the_oracle_disagrees_with_a_wrong_answer():
    """A request grounded by a stub that drops one match is counted wrong (the check can fail)."""
    (name, sc), = [(n, s) for n, s in request_corpus.scenes(0, 0) if n == "fetch_cans_1"]
    item = request_corpus.Item(name, "pick up a can", "pick", (request_corpus.Desc(type="can"),))

    class Stub:
        notes = ()
        interpretations = ()

    out = request_corpus.run_item(sc, item, lambda text, scene: Stub(), ValueError)
    assert out.verdict == "wrong"


def test_the_paraphrase_list_keeps_its_rate():
    """tests/corpus/paraphrases.yaml (written after the grammar): at least 90 % grounded exactly as meant."""
    from tools import paraphrases

    rows = paraphrases.check()
    right = sum(r[3] == r[2] for r in rows)
    assert len(rows) >= 50 and right / len(rows) >= 0.9, [(r[1], r[3]) for r in rows if r[3] != r[2]]
