"""Type stubs of the extension module ``impact._impact`` (Rust, PyO3). Use the functions of
:mod:`impact`; they wrap these and document the columns."""

from os import PathLike
from typing import Any, Literal

import numpy as np

Model = Literal["beam", "plate", "transient", "all"]

__version__: str
TRANSIENT_TOLERANCE: tuple[float, float]
DEFAULT_TOLERANCE: float

class SceneError(ValueError):
    """An invalid scene, with the command line's message (a bad argument is a plain
    ``ValueError`` with the same attributes)."""

    origin: str | None
    field: str | None
    value: float | None
    allowed: str | None
    low: float | None
    high: float | None
    unit: str | None

class SceneTypeError(SceneError, TypeError):
    """A scene dict's value of a type no scene holds (a complex number, a numpy datetime, an
    arbitrary object): a ``SceneError`` naming the field, and a ``TypeError``."""

class ModelError(RuntimeError):
    """A model that could not answer (budget exceeded, solver not converged)."""

class Scene:
    """A validated scene (SI units inside)."""

    @staticmethod
    def from_toml(path: str | PathLike[str]) -> Scene: ...
    @staticmethod
    def from_str(text: str, origin: str = "<string>") -> Scene: ...
    @staticmethod
    def from_dict(d: dict[str, Any], origin: str = "<dict>") -> Scene: ...
    @staticmethod
    def default() -> Scene: ...
    def to_toml_str(self) -> str: ...
    @property
    def name(self) -> str: ...
    @property
    def origin(self) -> str: ...
    @property
    def bodies(self) -> list[str]: ...
    @property
    def conditions(self) -> list[str]: ...
    @property
    def points_m(self) -> list[tuple[float, float]]: ...
    @property
    def velocities_m_per_s(self) -> list[float]: ...
    @property
    def analyses(self) -> list[str]: ...
    @property
    def plate_m(self) -> tuple[float, float, float]: ...
    @property
    def ensemble_size(self) -> int: ...
    def __reduce__(self) -> tuple[Any, tuple[str, str]]: ...

def run(
    scene: Scene,
    model: Model = "beam",
    sweep: float | None = None,
    yield_only: bool = False,
    tolerance: float | None = None,
    main_contact_share: float | None = None,
) -> dict[str, Any]: ...
def transient(
    scene: Scene,
    body: str,
    condition: str,
    x_mm: float,
    z_mm: float,
    velocity_m_per_s: float,
    error_estimate: bool = True,
    tolerance: float | None = None,
) -> dict[str, Any]: ...
def identify(
    scene: Scene,
    condition: str,
    start: float,
    stop: float,
    sensors_mm: list[tuple[float, float]] | None = None,
) -> dict[str, Any]: ...
def stream(scene: Scene) -> dict[str, Any]: ...
def stream_recording(scene: Scene, condition: str, stream: float, segment: float | None = None) -> dict[str, Any]: ...
def stream_segments(scene: Scene) -> tuple[int, float] | None: ...
def read_signal(signal: str) -> dict[str, Any]: ...
def drops(scene: Scene, signal: str) -> dict[str, Any]: ...
def tail_beam(scene: Scene) -> dict[str, Any]: ...

class Detector:
    """A trained window detector (``detector.json``, format impact-detector/1): the logistic
    model over every channel's features in sliding windows, with its channels, features,
    window, rate, alarm probability and provenance. The same code as ``impact detect``: the
    same file gives the same scores bit for bit."""

    @staticmethod
    def from_json(text: str) -> Detector: ...
    @staticmethod
    def load(path: str | PathLike[str]) -> Detector:
        """Reads a detector file; a file of another format, with unknown features or a model
        that does not match its channels is refused with a ValueError saying why."""
    def to_json(self) -> str: ...
    @property
    def channels(self) -> list[tuple[str, str]]:
        """(name, unit) of each channel, in the model's order."""
    @property
    def features(self) -> list[str]: ...
    @property
    def window_s(self) -> tuple[float, float]:
        """(window length, hop), s."""
    @property
    def rate_hz(self) -> float: ...
    @property
    def alarm_probability(self) -> float: ...
    @property
    def provenance(self) -> str:
        """Scene, its hash, support set, measurement chain and training windows, as JSON text."""
    def score(self, channels: list[np.ndarray], rate_hz: float) -> dict[str, np.ndarray]:
        """P(gangue-rich) of every window (W every H from the first sample, each wholly
        inside): columns ``start_s``, ``end_s``, ``probability_gangue_rich``, ``alarm``. The
        channels are float64 arrays of equal length, the detector's channels in order, at
        its rate; anything else is a ValueError naming it."""
    def detect(self, signal: str | PathLike[str]) -> dict[str, Any]:
        """Reads the recording whose sidecar is ``signal`` and scores it: ``scores`` (as
        ``score``), ``assessment`` (JSON text: delay, false alarms per hour and AUC after
        the sidecar's ``onset_s``; null without one), ``names``, ``rate_hz``."""
