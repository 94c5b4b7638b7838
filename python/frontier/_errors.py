"""The exceptions of the frontier module (raised by its C++ part, python/module.cpp)."""


class LoadError(ValueError):
    """A scene or model file that cannot be loaded, or a load keyword that is out of range.

    Attributes: file (str), line and column (int, 1-based; 0 where the error has no place in the
    file), message (str, without the place). str(error) is the command line's message,
    "FILE:LINE:COLUMN: error: MESSAGE".
    """

    def __init__(self, text, file, line, column, message):
        super().__init__(text)
        self.file = file
        self.line = line
        self.column = column
        self.message = message


class SimulationError(RuntimeError):
    """A step that blew up or a joint that came apart: the run cannot go on from this state.

    Attributes: step (int), time (s), body (name of the runaway body or the joint's child),
    quantity ("position", "velocity", "angular velocity", "orientation", ...), joint (name or
    None). A state saved earlier with Simulator.get_state() can be restored.
    """

    def __init__(self, text, step, time, body, quantity, joint):
        super().__init__(text)
        self.step = step
        self.time = time
        self.body = body
        self.quantity = quantity
        self.joint = joint


class UnknownNameError(KeyError):
    """A body, joint or actuator name the model does not have (the message names the nearest)."""

    def __str__(self):
        return str(self.args[0]) if self.args else ""
