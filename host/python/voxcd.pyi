# Type stubs of the voxcd Python module (host/python, docs/python.md): every public name, installed beside the module
# (lib/python3/dist-packages/voxcd.pyi) so that editors and type checkers complete it. tests/host/python/test_stubs.py
# checks that the stub and the module agree: the same names, and the same parameters in the same order.
import os
from typing import Any, Dict, List, Optional, Sequence, Tuple, Union, overload

import numpy as np
import numpy.typing as npt

__version__: str

# A pose (docs/python.md, "Poses"): None (the identity), 3, 6, 7, 12 or 16 numbers, a 3 x 4 or 4 x 4 matrix, (R, t),
# or the dict `voxcd pair --json` prints; some calls also take an array of poses.
_Pose = Union[None, Sequence[float], npt.ArrayLike, Tuple[npt.ArrayLike, npt.ArrayLike], Dict[str, Sequence[float]]]
_Path = Union[str, "os.PathLike[str]"]
# A mesh given as arrays: (vertices, faces), or an object with .vertices and .faces (trimesh) or .triangles (Open3D).
_Mesh = Any
# An object argument: an Object, or anything voxelize() takes (a mesh file, a shape, arrays, a mesh object).
_ObjectLike = Union["Object", _Path, _Mesh]
_Vec3 = Union[None, Sequence[float], npt.ArrayLike]
_Array = npt.NDArray[Any]

EMPTY: int
SURFACE: int
INTERIOR: int

# Errors (docs/python.md, "Errors"): Error and one class per error of the library, also a ValueError for bad input.
class Error(RuntimeError):
    where: str

class RangeError(Error, ValueError): ...
class ConfigError(Error, ValueError): ...
class JobError(Error): ...
class VectorError(Error, ValueError): ...
class MeshError(Error, ValueError): ...
class ObjectFileError(Error, ValueError): ...
class CapacityError(Error, ValueError): ...
class DeviceError(Error): ...
class SceneFileError(Error, ValueError): ...

class OptionError(Error, ValueError):
    options: List[str]

class PlacementError(Error, ValueError): ...
class RecordError(Error, ValueError): ...

class SizeError(Error, ValueError):
    constraint: str
    factor: float

class BodyError(Error, ValueError):
    body: BodyId
    field: str

class TimingTableError(Error): ...
class EnergyTableError(Error): ...

# The module.
def backends() -> List[str]: ...
def backend_status() -> List[Dict[str, Any]]: ...
def shapes() -> List[str]: ...
def broadphases() -> List[str]: ...

# Objects (docs/objects.md).
class Object:
    @staticmethod
    def load(
        file_or_shape: _Path,
        *,
        voxel: float = 0.0,
        resolution: int = 32,
        distance_bits: int = 0,
        band: float = 4.0,
        storage: str = "dense",
        strict: bool = False,
        threads: int = 0,
    ) -> Object: ...
    @staticmethod
    def from_arrays(
        vertices: npt.ArrayLike,
        triangles: npt.ArrayLike,
        *,
        voxel: float = 0.0,
        resolution: int = 32,
        distance_bits: int = 0,
        band: float = 4.0,
        storage: str = "dense",
        strict: bool = False,
        threads: int = 0,
    ) -> Object: ...
    @property
    def source(self) -> str: ...
    @property
    def source_hash(self) -> int: ...
    @property
    def voxel(self) -> float: ...
    @property
    def origin(self) -> _Array: ...
    @property
    def dims(self) -> Tuple[int, int, int]: ...
    @property
    def states(self) -> npt.NDArray[np.uint8]: ...
    @property
    def counts(self) -> Dict[str, int]: ...
    @property
    def shell_points(self) -> npt.NDArray[np.float64]: ...
    @property
    def shell_normals(self) -> npt.NDArray[np.float64]: ...
    @property
    def shell_count(self) -> int: ...
    @property
    def shell_cells(self) -> npt.NDArray[np.uint32]: ...
    @property
    def shell_on_surface(self) -> bool: ...
    @property
    def shell_spacing(self) -> float: ...
    @property
    def shell_origin(self) -> npt.NDArray[np.float64]: ...
    @property
    def shell_dims(self) -> Tuple[int, int, int]: ...
    @property
    def shell_ratio(self) -> float: ...
    @property
    def distance_bits(self) -> int: ...
    @property
    def distance_step(self) -> float: ...
    @property
    def distance(self) -> Optional[npt.NDArray[np.int16]]: ...
    @property
    def storage(self) -> Dict[str, Optional[str]]: ...
    @property
    def memory(self) -> Dict[str, Optional[Dict[str, Optional[int]]]]: ...
    @property
    def bricks(self) -> Dict[str, Any]: ...
    @property
    def report(self) -> Optional[Dict[str, Any]]: ...
    @property
    def repair(self) -> Optional[Dict[str, Any]]: ...  # deprecated: report
    def save(self, path: _Path) -> None: ...

def voxelize(
    source: Union[_Path, _Mesh],
    *,
    voxel: Optional[float] = None,
    resolution: Optional[int] = None,
    shell_ratio: float = 1.4142135623730951,
    strict: bool = False,
    threads: int = 0,
    distance_bits: int = 0,
    band: float = 4.0,
    storage: str = "auto",
) -> Object: ...
def read_object(path: _Path) -> Object: ...

# One pair query, and repeated queries (docs/api.md): the C++ collide() and Collider. Each result is a dict: hits,
# lookups, device_cycles and the contacts as arrays (a_in_b, points, positions, normals, voxels, states, depths).
@overload
def collide(
    a: _ObjectLike,
    pose_a: _Pose,
    b: _ObjectLike,
    pose_b: _Pose,
    *,
    mode: str = "ALL",
    both_directions: bool = True,
    margin: float = 0.0,
    backend: str = "cpu",
    lanes: int = 4,
    threads: int = 0,
    both: Optional[bool] = None,
) -> Dict[str, Any]: ...
@overload
def collide(
    a: _ObjectLike,
    b: _ObjectLike,
    poses: Sequence[Tuple[_Pose, _Pose]],
    *,
    mode: str = "ALL",
    both_directions: bool = True,
    margin: float = 0.0,
    backend: str = "cpu",
    lanes: int = 4,
    threads: int = 0,
    both: Optional[bool] = None,
) -> List[Dict[str, Any]]: ...

class Collider:
    def __init__(
        self,
        *,
        mode: str = "ALL",
        both_directions: bool = True,
        margin: float = 0.0,
        backend: str = "cpu",
        lanes: int = 4,
        threads: int = 0,
        both: Optional[bool] = None,
    ) -> None: ...
    @overload
    def collide(self, a: _ObjectLike, pose_a: _Pose, b: _ObjectLike, pose_b: _Pose) -> Dict[str, Any]: ...
    @overload
    def collide(self, a: _ObjectLike, b: _ObjectLike, poses: Sequence[Tuple[_Pose, _Pose]]) -> List[Dict[str, Any]]: ...
    @property
    def options(self) -> Dict[str, Any]: ...
    @property
    def worker_threads(self) -> int: ...

# Pair tests as `voxcd pair` runs them (docs/pairs.md).
class Pair:
    def __init__(
        self,
        a: Union[Object, _Path],
        b: Union[Object, _Path],
        *,
        voxel: Optional[float] = None,
        resolution: Optional[int] = None,
        backend: str = "cpu",
        lanes: int = 4,
        distance_bits: Optional[int] = None,
        band: Optional[float] = None,
        margin: Optional[float] = None,
        threads: int = 0,
    ) -> None: ...
    def query(
        self,
        pose: _Pose = None,
        *,
        mode: str = "ALL",
        both_directions: bool = True,
        cull: bool = True,
        both: Optional[bool] = None,
    ) -> Union[Dict[str, Any], List[Dict[str, Any]]]: ...
    def contacts(
        self,
        pose: _Pose = None,
        *,
        mode: str = "ALL",
        both_directions: bool = True,
        cull: bool = True,
        both: Optional[bool] = None,
    ) -> Dict[str, Any]: ...
    @property
    def voxel(self) -> float: ...
    @property
    def backend(self) -> str: ...
    @property
    def distance_bits(self) -> int: ...
    @property
    def band(self) -> Optional[Tuple[float, float]]: ...
    @property
    def margin(self) -> float: ...
    @property
    def device(self) -> str: ...
    @property
    def a(self) -> Object: ...
    @property
    def b(self) -> Object: ...

def pair(
    a: Union[Object, _Path],
    b: Union[Object, _Path],
    pose: _Pose = None,
    *,
    voxel: Optional[float] = None,
    resolution: Optional[int] = None,
    backend: str = "cpu",
    lanes: int = 4,
    mode: str = "ALL",
    both_directions: bool = True,
    cull: bool = True,
    distance_bits: Optional[int] = None,
    band: Optional[float] = None,
    margin: Optional[float] = None,
    both: Optional[bool] = None,
) -> Union[Dict[str, Any], List[Dict[str, Any]]]: ...

# A world the caller steps (docs/api.md, docs/simulate.md).
class BodyId:
    @overload
    def __init__(self) -> None: ...
    @overload
    def __init__(self, index: int, generation: int) -> None: ...
    @property
    def index(self) -> int: ...
    @property
    def generation(self) -> int: ...
    def __eq__(self, arg0: object) -> bool: ...
    def __hash__(self) -> int: ...

class World:
    def __init__(
        self,
        *,
        side: float = 100.0,
        walls: bool = True,
        response: bool = True,
        broadphase: Optional[str] = None,
        backend: str = "cpu",
        lanes: int = 4,
        mode: str = "ALL",
        both_directions: bool = True,
        distance_bits: int = 0,
        margin: float = 0.0,
        ccd: bool = False,
        threads: int = 0,
        pruning: Optional[str] = None,
        both: Optional[bool] = None,
    ) -> None: ...
    @staticmethod
    def scene(
        scene: Union[None, _Path, Dict[str, Any]] = None,
        *,
        frames: Optional[int] = None,
        objects: Optional[int] = None,
        shape: Optional[str] = None,
        voxel: Optional[float] = None,
        resolution: Optional[int] = None,
        density: Optional[float] = None,
        speed: Optional[float] = None,
        seed: Optional[int] = None,
        broadphase: Optional[str] = None,
        backend: Optional[str] = None,
        lanes: Optional[int] = None,
        mode: Optional[str] = None,
        both_directions: Optional[bool] = None,
        clock: Optional[float] = None,
        config: Optional[str] = None,
        threads: int = 0,
        midphase: bool = True,
        cull: bool = True,
        distance_bits: Optional[int] = None,
        band: Optional[float] = None,
        margin: Optional[float] = None,
        ccd: Optional[bool] = None,
        pruning: Optional[str] = None,
        both: Optional[bool] = None,
    ) -> World: ...
    def add(
        self,
        object: _ObjectLike,
        pose: _Pose = None,
        *,
        velocity: _Vec3 = None,
        angular_velocity: _Vec3 = None,
        user_data: Any = None,
        kind: str = "dynamic",
        enabled: bool = True,
    ) -> BodyId: ...
    def add_body(self, object: _ObjectLike, pose: _Pose = None, *, velocity: _Vec3 = None, spin: _Vec3 = None) -> int: ...
    def remove(self, id: BodyId) -> None: ...
    def is_valid(self, id: BodyId) -> bool: ...
    def pose(self, id: BodyId) -> npt.NDArray[np.float64]: ...
    def set_pose(self, id: BodyId, pose: _Pose) -> None: ...
    def velocity(self, id: BodyId) -> npt.NDArray[np.float64]: ...
    def set_velocity(self, id: BodyId, velocity: _Vec3) -> None: ...
    def angular_velocity(self, id: BodyId) -> npt.NDArray[np.float64]: ...
    def set_angular_velocity(self, id: BodyId, angular_velocity: _Vec3) -> None: ...
    def user_data(self, id: BodyId) -> Any: ...
    def set_user_data(self, id: BodyId, user_data: Any) -> None: ...
    def kind(self, id: BodyId) -> str: ...
    def is_enabled(self, id: BodyId) -> bool: ...
    def set_enabled(self, id: BodyId, enabled: bool) -> None: ...
    def __len__(self) -> int: ...
    @property
    def ids(self) -> List[BodyId]: ...
    @property
    def positions(self) -> npt.NDArray[np.float64]: ...
    @property
    def orientations(self) -> npt.NDArray[np.float64]: ...
    @property
    def poses(self) -> npt.NDArray[np.float64]: ...
    @property
    def velocities(self) -> npt.NDArray[np.float64]: ...
    def step(self, dt: Optional[float] = None) -> Dict[str, Any]: ...
    @property
    def frame(self) -> int: ...
    @property
    def state_hash(self) -> str: ...
    @property
    def pairs(self) -> npt.NDArray[np.uint32]: ...
    @property
    def contacts(self) -> List[Dict[str, Any]]: ...
    @property
    def begin_events(self) -> List[Dict[str, Any]]: ...
    @property
    def end_events(self) -> List[Dict[str, Any]]: ...
    @property
    def touching(self) -> List[Dict[str, Any]]: ...
    def record(self, path: str) -> None: ...
    def stop_recording(self) -> None: ...

# Scenes (docs/simulate.md, docs/scenes.md, docs/size.md).
def simulate(
    scene: Union[None, _Path, Dict[str, Any]] = None,
    *,
    frames: Optional[int] = None,
    objects: Optional[int] = None,
    shape: Optional[str] = None,
    voxel: Optional[float] = None,
    resolution: Optional[int] = None,
    density: Optional[float] = None,
    speed: Optional[float] = None,
    seed: Optional[int] = None,
    broadphase: Optional[str] = None,
    backend: Optional[str] = None,
    lanes: Optional[int] = None,
    mode: Optional[str] = None,
    both_directions: Optional[bool] = None,
    clock: Optional[float] = None,
    config: Optional[str] = None,
    threads: int = 0,
    midphase: bool = True,
    cull: bool = True,
    distance_bits: Optional[int] = None,
    band: Optional[float] = None,
    margin: Optional[float] = None,
    ccd: Optional[bool] = None,
    pruning: Optional[str] = None,
    both: Optional[bool] = None,
    record: Optional[_Path] = None,
) -> Dict[str, Any]: ...
def size(
    scene: Union[_Path, Dict[str, Any]],
    *,
    accuracy: Optional[float] = None,
    contact_accuracy: Optional[float] = None,
    rate: Optional[float] = None,
    clock: Optional[float] = None,
    frames: Optional[int] = None,
    cost: bool = False,
    rtl: Optional[_Path] = None,
    target: Optional[str] = None,
) -> Dict[str, Any]: ...
def read_recording(path: _Path) -> Dict[str, Any]: ...

# Conformance vectors (docs/conformance.md).
def generate_vectors(
    path: _Path,
    *,
    seed: int = 1,
    jobs: int = 200,
    cloud_points: int = 2000,
    lanes: Optional[int] = None,
    config: Optional[str] = None,
) -> Dict[str, Any]: ...
def conform(
    files: Union[_Path, Sequence[_Path]],
    *,
    backend: str = "ref",
    lanes: Optional[int] = None,
    cycles: bool = False,
) -> Dict[str, Any]: ...
