"""Import MoveIt planning scenes (YAML) as lazyground scenes (#15).

    from lazyground.moveit import ImportOptions, import_moveit_file
    result = import_moveit_file("scene.yml", "yaml_scenes/mine.yaml", ImportOptions(robot="fetch"))
    print(result.summary.line())

Modules (what a file is: ``lazyground.scene.file_kind``): ``types`` (object types from id tokens and
geometry), ``start`` (start states and joint limits), ``meshes`` (finding mesh files),
``convert`` (mapping -> scene mapping), ``importer`` (files, atomic output). No pydrake
except the start check, which is skipped without it.
"""

from lazyground.moveit.convert import ImportOptions, ImportSummary, convert_moveit
from lazyground.moveit.importer import ImportResult, import_moveit_file
from lazyground.moveit.start import StartOptions
from lazyground.moveit.types import classify, parse_rule, tokens, word_type

__all__ = ["ImportOptions", "ImportResult", "ImportSummary", "StartOptions", "classify", "convert_moveit",
           "import_moveit_file", "parse_rule", "tokens", "word_type"]
