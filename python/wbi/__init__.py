"""wbi for Python: the model library, the whole-body interface over DDS, a
periodic loop for controllers, and wbi recordings as numpy arrays.

    import wbi
    model = wbi.Model.from_urdf("models/arm7.urdf")
    robot = wbi.DdsInterface(robot="arm", urdf="models/arm7.urdf", joints=[...])
    loop = wbi.PeriodicLoop(1000)
    rec = wbi.Recording("run.mcap")
    host = wbi.ControllerHost("arm")      # switch controllers, set their parameters
    com = wbi.ReferenceWriter("humanoid", "balance", "com")  # a controller's reference input

See python/README.md.
"""

from ._wbi import (ControlMode, ControlParameter, ControllerHost, DdsInterface, Error, ReferenceWriter,
                   EstimateKind, Model, ReadMode, SensorKind, StaleDataError, Stamp, TimeoutError)
from .loop import LoopStatistics, PeriodicLoop
from .recording import Recording, RecordingError, TopicData

__all__ = ["ControlMode", "ControlParameter", "ControllerHost", "DdsInterface", "Error", "EstimateKind", "Model", "ReferenceWriter",
           "ReadMode", "SensorKind", "StaleDataError", "Stamp", "TimeoutError", "LoopStatistics",
           "PeriodicLoop", "Recording", "RecordingError", "TopicData"]
