"""Play and record (lsc_device_play, lsc_device_record): an lsc.Action on a
schedule fixed from one start."""
import ctypes
import time
from typing import TYPE_CHECKING, Any, Callable, Dict, Iterable, NamedTuple, Optional, Union

from . import _native as N
from .action import Action
from .arm import Key, servo_id as _servo_id
from ._check import integer as _int, shown as _shown
from .errors import invalid, wrong_type
from ._handle import _Handle, _keys


class PlayStep(NamedTuple):
    """A frame lsc.Controller.play sent (to its progress callback)."""
    keyframe: int            #: 0..len(action)-1
    repetition: int          #: 0..times-1
    lead_in: bool            #: the move to keyframe 0 over lead_ms
    due_ms: int              #: when it was due, ms after the start
    time_ms: int             #: the move's time
    servos: Dict[int, int]   #: id -> position (servos that did not change are left out)
    dropped: int             #: keyframes dropped just before it (the line could not keep up)


class PlayResult(NamedTuple):
    """What a play did."""
    frames: int         #: frames sent
    dropped: int        #: keyframes dropped: faster than the line carries
    keyframe: int       #: 1-based keyframe of the last frame sent (0: none)
    max_late_ms: int    #: the latest a frame went out after its due time
    total_ms: int       #: the whole schedule: the end of the last move after the start
    stopped: bool       #: the progress callback stopped it


class _Play(_Handle):
    """lsc.Controller's play and record."""

    if TYPE_CHECKING:
        def unload(self, servos: Union[Key, Iterable[Key]]) -> None: ...

    # ---- play and record ------------------------------------------------------------

    def play(self, action: Action, lead_ms: int = 1000, speed: int = 100, times: int = 1,
             baud: int = 0, progress: Optional[Callable[[Optional[PlayStep], int], Any]] = None
             ) -> PlayResult:
        """Plays action on a schedule fixed from one start (as lscctl play):
        the first move to keyframe 0 over lead_ms, then each keyframe when the
        move before it ends; speed in percent (200: twice as fast); times
        repetitions; baud: the line the "cannot keep up" rule models (0: the
        port's). With an arm profile every keyframe is checked first
        (lsc.InvalidArgument naming the keyframe and joint, nothing sent).

        progress(step, elapsed_ms), if given, is called after each frame sent
        (a PlayStep) and at least every 100 ms while waiting (None); returning
        False stops the play (the servos stay where they are). Ctrl-C stops it
        the same way, then raises KeyboardInterrupt."""
        if not isinstance(action, Action):
            raise wrong_type("play takes an lsc.Action, not %s" % _shown(action))
        if len(action) == 0:
            raise invalid("the action has no keyframes")
        cfg = N.PlayerConfig(_int("speed", speed, 1, 65535), _int("times", times, 1, 65535),
                             _int("lead_ms", lead_ms, 0, 65535), 0)
        cfg.baud = _int("baud", baud, 0, N.LSC_DEVICE_FOREVER)

        def tramp(_user: Any, step: Any, elapsed: int) -> bool:
            if self._pending is not None:
                return False
            try:
                if progress is None:
                    return True
                s = None
                if step:
                    c = step.contents
                    s = PlayStep(c.keyframe, c.repetition, bool(c.lead_in), c.due_ms, c.time_ms,
                                 {c.servos[i].id: c.servos[i].position
                                  for i in range(c.nservos)}, c.dropped)
                return progress(s, elapsed) is not False
            except BaseException as e:  # noqa: B902 (re-raised after the C call)
                self._pending = e
                return False
        fn = N.PLAY_FN(tramp)
        result = N.PlayResult()
        if self._long_call(N.lib.lsc_device_play, ctypes.byref(action._a), ctypes.byref(cfg),
                           fn, None, ctypes.byref(result)):
            result.stopped = True
        return PlayResult(result.frames, result.dropped, result.keyframe, result.max_late_ms,
                          result.total_ms, bool(result.stopped))

    def record(self, servos: Union[Key, Iterable[Key]], every_ms: int, count: int,
               unload: bool = True,
               progress: Optional[Callable[[Action, bool], Any]] = None) -> Action:
        """Records count keyframes (1..) of servos, one every every_ms ms
        (1..65535) on a schedule fixed from one start, and returns them as an
        Action. unload=True first powers the servos off so that they can be
        posed by hand. progress(action, taken), if given, is called after each
        keyframe (taken True) and at least every 100 ms while waiting; False
        ends the recording early."""
        keys = self._expand(_keys(servos))
        ids = [_servo_id(self._arm, k) for k in keys]
        every_ms = _int("every_ms", every_ms, 1, 65535)
        count = _int("count", count, 1, 1 << 24)
        action = Action(ids)
        if unload:
            self.unload(ids)

        def tramp(_user: Any, _a: Any, taken: int) -> bool:
            if self._pending is not None:
                return False
            try:
                return progress is None or progress(action, bool(taken)) is not False
            except BaseException as e:  # noqa: B902 (re-raised after the C call)
                self._pending = e
                return False
        fn = N.RECORD_FN(tramp)
        self._long_call(N.lib.lsc_device_record, ctypes.byref(action._a), every_ms, count, fn,
                        None)
        return action
