"""Type stubs of the compiled module ``rocking._rocking`` (see ``rocking/__init__.py`` for the
public API built on it)."""

from typing import Any, Dict, List, Optional, Sequence, Tuple, Union

__version__: str

class SimulationError(RuntimeError):
    """A run failed though its input was valid."""

class Scene:
    """A scene loaded and validated with its overrides."""

    @staticmethod
    def load(path: str, set: Sequence[str] = ...) -> "Scene": ...
    @staticmethod
    def from_text(text: str, path: str, set: Sequence[str] = ...) -> "Scene": ...
    @property
    def path(self) -> str: ...
    @property
    def text(self) -> str: ...
    @property
    def sets(self) -> List[str]: ...
    @property
    def title(self) -> Optional[str]: ...
    @property
    def kernel_variant(self) -> Tuple[str, List[str]]: ...
    def run(self) -> "RunOutput": ...

class RunOutput:
    """One simulation's results."""

    @property
    def summary_json(self) -> str: ...
    def history(self) -> Optional[Dict[str, Union[bytes, List[str]]]]: ...
    def events(self) -> Optional[Dict[str, Union[bytes, List[str]]]]: ...
    def animation(
        self,
        frames: Optional[int] = None,
        width: Optional[int] = None,
        height: Optional[int] = None,
    ) -> bytes: ...

def spectrum(
    scene: Scene, axes: Sequence[str] = ..., threads: Optional[int] = None
) -> Dict[str, Any]: ...
def batch(
    scene: Scene,
    records: Sequence[str] = ...,
    scales: Sequence[float] = ...,
    threads: Optional[int] = None,
    axes: Sequence[str] = ...,
) -> Dict[str, Any]: ...
def ida(
    scene: Scene, records: Sequence[str] = ..., threads: Optional[int] = None
) -> Tuple[str, str]: ...
def models_json() -> str: ...
def read_scene(path: str) -> str: ...
def figure(
    path: str, cache: str, cells: Optional[int] = None, draft: bool = False, quiet: bool = True
) -> Dict[str, bytes]: ...
