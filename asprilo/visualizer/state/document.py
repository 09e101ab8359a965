"""The document the viewer shows and edits, without Qt: a :class:`Scenario` (instance, plan,
domain, the files they came from), the undo history of edits to instance and plan, and
whether either has unsaved edits.

Edits of the instance always change its initial state; edits of the plan replace it as a
whole.  Both go through the history, so Undo takes back the last one whatever it was.  A search
that finds better and better plans shows each as a *draft* outside the history; its result
then goes in as one step (or the plan from before comes back).
Observers learn of a new scenario through ``opened`` and of every change (done, undone,
or a plan growing in an online session) through ``changed``.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

from asprilo.domain import Domain, detect_domain
from asprilo.errors import InputError
from asprilo.model import Instance, Plan
from asprilo.sources import Source
from asprilo.writer import format_instance, format_plan, header_lines, write_text

from . import edits
from .edits import Edit
from .history import Group, History, Step
from .loading import Scenario
from .observe import Signal
from .rules import varied

if TYPE_CHECKING:
    from asprilo.domain.variant_file import VariantFile

TOOL = "asprilo viz"
INSTANCE, PLAN = "instance", "plan"


@dataclass(frozen=True)
class Change:
    """What changed: the instance (``edit``: its tables and entries) and/or the plan, and
    the time to show afterwards (``None``: keep the time shown)."""

    edit: Edit | None = None
    plan: bool = False
    time: float | None = None


class _InstanceStep:
    part = INSTANCE

    def __init__(self, document: Document, edit: Edit):
        self.document, self.edit, self.text = document, edit, edit.text

    def redo(self) -> None:
        self.document.apply(self.edit)

    def undo(self) -> None:
        self.document.apply(self.edit, undo=True)


class _PlanStep:
    part = PLAN

    def __init__(self, document: Document, after: Plan, sources: list[Source], text: str, time: float | None,
                 solved_in: Domain | None):
        scenario = document.scenario
        assert scenario is not None  # (a plan is replaced only in a scenario shown)
        self.document, self.text, self.time = document, text, time
        self.before = (scenario.plan, scenario.plan_sources, scenario.solved_in)
        self.after = (after, sources, solved_in)

    def redo(self) -> None:
        plan, sources, solved_in = self.after
        self.document.put_plan(plan, sources, self.time, solved_in)

    def undo(self) -> None:
        plan, sources, solved_in = self.before
        self.document.put_plan(plan, sources, self.time, solved_in)


def _touches(step: Step, part: str) -> bool:
    if isinstance(step, Group):
        return any(_touches(inner, part) for inner in step.steps)
    return getattr(step, "part", None) == part


class Document:
    """The scenario shown, its history and the file Save writes the instance to."""

    def __init__(self) -> None:
        self.scenario: Scenario | None = None
        self.history = History()
        self.path: Path | None = None  # where Save instance writes (None: ask)
        self._empty = Instance()
        self._modified = False
        #: the plan a draft covers (with its sources and the domain a solve found it for)
        self._before_draft: tuple[Plan, list[Source], Domain | None] | None = None
        #: the rule variants every scenario is shown under (``viz --variant``)
        self.variants: tuple[VariantFile, ...] = ()
        self.opened = Signal()            # (keep_time: bool) another scenario, or none
        self.changed = Signal()           # (Change) an edit done or undone, or the plan grew
        self.modified_changed = Signal()  # (modified: bool)
        self.saved = Signal()             # the instance or the plan was written to a file
        self.history.changed.connect(self._history_changed)

    @property
    def instance(self) -> Instance:
        return self.scenario.instance if self.scenario is not None else self._empty

    @property
    def plan(self) -> Plan:
        return self.scenario.plan if self.scenario is not None else Plan()

    @property
    def base_domain(self) -> Domain:
        """The scenario's domain before the variants: given, the one a solve found the plan
        shown for, or detected from instance and plan."""
        scenario = self.scenario
        given = scenario.domain or scenario.solved_in if scenario is not None else None
        return given or detect_domain(self.instance, self.plan if len(self.plan) else None)

    @property
    def domain(self) -> Domain:
        """The scenario's domain (:attr:`base_domain`) changed by the variants (unchanged where
        they do not fit it: the window said so when it was opened)."""
        domain = self.base_domain
        try:
            return varied(domain, self.variants)
        except InputError:
            return domain

    def follow_variants(self, variants: Sequence[VariantFile]) -> None:
        """Show every scenario under the rule ``variants`` from now on (loaded variant files)."""
        self.variants = tuple(variants)

    # --- opening ------------------------------------------------------------------------------

    def open(self, scenario: Scenario | None, keep_time: bool = False) -> None:
        """Show and edit ``scenario`` from now on (``None``: nothing); a new history."""
        self.scenario = scenario
        self.path = _own_file(scenario)
        self._before_draft = None
        self.history.clear()
        self.opened.emit(keep_time)

    # --- changes --------------------------------------------------------------------------------

    def perform(self, edit: Edit) -> bool:
        """Do an edit of the instance as one undoable step; ``False`` when it changes nothing."""
        if self.scenario is None or not edit.changes:
            return False
        self.history.push(_InstanceStep(self, edit))
        return True

    def replace_plan(self, plan: Plan, text: str, time: float | None = None,
                     sources: list[Source] | None = None, solved_in: Domain | None = None) -> bool:
        """Show ``plan`` instead of the plan shown, as one undoable step; ``sources``: where
        it comes from now (default: where the plan shown came from); ``solved_in``: the domain
        a solve found it for, which it is then shown under (``None``: detected again).  A draft
        shown ends: the step replaces the plan from before the draft."""
        if self.scenario is None:
            return False
        before, self._before_draft = self._before_draft, None
        drafted = before is not None
        if before is not None:  # the step goes from the plan the draft covers
            self.scenario.plan, self.scenario.plan_sources, self.scenario.solved_in = before
        if plan == self.scenario.plan:
            if drafted:  # the plan from before the draft, shown again
                self.put_plan(plan, self.scenario.plan_sources, time, self.scenario.solved_in)
            return False
        sources = self.scenario.plan_sources if sources is None else sources
        self.history.push(_PlanStep(self, plan, sources, text, time, solved_in))
        return True

    def draft_plan(self, plan: Plan, solved_in: Domain | None = None) -> None:
        """Show ``plan`` for now, outside the history (a search's better plans as they come, for
        the domain ``solved_in``), until :meth:`replace_plan` puts the result in as one step or
        :meth:`drop_draft` ends it."""
        if self.scenario is None:
            return
        if self._before_draft is None:
            self._before_draft = (self.scenario.plan, self.scenario.plan_sources, self.scenario.solved_in)
        self.put_plan(plan, [], None, solved_in)

    def drop_draft(self) -> None:
        """Show the plan from before the draft again (the search failed or was dropped)."""
        if self._before_draft is not None:
            (plan, sources, solved_in), self._before_draft = self._before_draft, None
            self.put_plan(plan, sources, None, solved_in)

    def grow_plan(self, plan: Plan) -> None:
        """The plan of an online session grew (not undoable: the session owns it)."""
        self.put_plan(plan, self.scenario.plan_sources, None)

    def refresh(self, time: float | None = None) -> None:
        """Tell observers that the scenario changed in place (a world that grew, a session ended)."""
        self.changed.emit(Change(time=time))

    def apply(self, edit: Edit, undo: bool = False) -> None:
        edits.apply(self.instance, edit, undo)
        self.changed.emit(Change(edit=edit, time=0.0))

    def put_plan(self, plan: Plan, sources: list[Source], time: float | None, solved_in: Domain | None = None) -> None:
        scenario = self.scenario
        assert scenario is not None  # (a plan is put only in a scenario shown)
        scenario.plan, scenario.plan_sources, scenario.solved_in = plan, sources, solved_in
        self.changed.emit(Change(plan=True, time=time))

    # --- unsaved edits ------------------------------------------------------------------------

    def unsaved(self, part: str) -> bool:
        """Whether the instance (``INSTANCE``) or the plan (``PLAN``) differs from its file."""
        steps = self.history.since(part)
        return steps is None or any(_touches(step, part) for step in steps)

    @property
    def modified(self) -> bool:
        return self._modified

    def _history_changed(self) -> None:
        modified = self.unsaved(INSTANCE) or self.unsaved(PLAN)
        if modified != self._modified:
            self._modified = modified
            self.modified_changed.emit(modified)

    # --- files ------------------------------------------------------------------------------------

    def text(self) -> str:
        """The instance in the canonical format, with a header naming the viewer."""
        return format_instance(self.instance, header_lines(self.instance, tool=TOOL))

    def loaded(self, part: str | None = None) -> list[str]:
        """The files the scenario was read from that writing ``part`` must not replace: saving
        the instance (``INSTANCE``) may replace the instance's own file, saving the plan
        (``PLAN``) the plan's, unless the other part came from that file too; a template or a
        picture (``None``) replaces none of them."""
        if self.scenario is None:
            return []
        instances, plans = self.scenario.files
        if part == INSTANCE:
            shared = len(self.scenario.plan) and not self.scenario.plan_sources  # the plan came from there
            return plans + instances if shared else plans
        return instances if part == PLAN else instances + plans

    def save(self, path: str | Path) -> None:
        """Write the instance (atomically); the scenario now comes from that file."""
        text = self.text()
        write_text(path, text, self.loaded(INSTANCE))
        self.path = Path(path)
        scenario = self.scenario
        if scenario is not None:
            if len(scenario.plan) and not scenario.plan_sources:
                scenario.plan_sources = scenario.instance_sources  # the plan still comes from there
            scenario.instance_sources = [Source(str(path), text)]
        self.history.mark(INSTANCE)
        self._history_changed()
        self.saved.emit()

    def save_template(self, path: str | Path) -> None:
        """Write the layout without products and orders, for ``gen -T FILE``."""
        template = edits.template_of(self.instance)
        header = header_lines(template, tool=TOOL)
        header[1:1] = [f"template for the generator: gen -T {Path(path).name} (adds products and orders)"]
        write_text(path, format_instance(template, header), self.loaded())

    def save_plan(self, path: str | Path) -> None:
        """Write the plan shown (atomically); the scenario's plan now comes from that file."""
        text = format_plan(self.plan)
        write_text(path, text, self.loaded(PLAN))
        if self.scenario is not None:
            self.scenario.plan_sources = [Source(str(path), text)]
        self.history.mark(PLAN)
        self._history_changed()
        self.saved.emit()


def _own_file(scenario: Scenario | None) -> Path | None:
    """The file Save writes to: the scenario's one instance file, unless it also holds the plan."""
    if scenario is None:
        return None
    instances, _plans = scenario.files
    if len(scenario.instance_sources) != 1 or len(instances) != 1:
        return None
    if len(scenario.plan) and not scenario.plan_sources:
        return None  # the plan came from the instance file: saving the instance would lose it
    return Path(instances[0])
