r"""``sin`` and ``cos`` as straight-line arithmetic, so that loops over lanes vectorise.

``np.sin``/``np.cos`` compile to calls into the C library, which keeps a loop over robots
scalar. :func:`sincos` is branch-free double-precision arithmetic (the algorithm of fdlibm,
the C library of FreeBSD and Sun, with its constants) that LLVM inlines and turns into
packed vector instructions:

1. **Cody-Waite range reduction**: :math:`k = \mathrm{round}(x\cdot 2/\pi)` (the 1.5·2⁵²
   rounding trick), :math:`r = x - k\,\pi/2` with :math:`\pi/2` split into three 33-bit
   parts and a 53-bit tail (fdlibm's ``pio2_1, pio2_2, pio2_3, pio2_3t``): each product
   :math:`k\cdot` part is exact for :math:`|k| < 2^{20}`, the first difference is exact
   (Sterbenz) and the next two are error-free sums (Knuth's TwoSum), so
   :math:`r = y_0 + y_1` is good to about 150 bits and no cancellation near a multiple of
   :math:`\pi/2` is lost. (fdlibm takes the extra rounds only when it detects cancellation;
   here they are always taken, with TwoSum, which keeps the code branch-free.)
2. **Minimax polynomials** on :math:`[-\pi/4, \pi/4]`: fdlibm's ``__kernel_sin`` (degree 13,
   :math:`|\sin r - p(r)| < 2^{-58}`) and ``__kernel_cos`` (degree 14, with the
   :math:`1 - r^2/2` split that keeps the last bit), both using the tail :math:`y_1`.
3. **Quadrant** :math:`q = k \bmod 4` (computed in floating point, exact): sin, cos are
   :math:`(s, c), (c, -s), (-s, -c), (-c, s)` of the kernel values, by selects.

Accuracy (tested against the C library's ``sin``/``cos`` on 10⁶ random angles of
:math:`|x| \le 10^5` and around multiples of :math:`\pi/2`): at most 1 ulp apart (C's are
themselves within 1 ulp), i.e. ≤ 2 ulp from the true value. Valid for
:math:`|x| \le` :data:`SINCOS_MAX_ABS` (:math:`2^{19}\pi`); beyond it the reduction loses
exactness and the lane kernels take ``np.sin``/``np.cos`` for that robot
(:func:`kernels.motion_lanes`).
"""

from ._jit import kernel

#: |x| up to which :func:`sincos` is within the stated accuracy (|k| < 2^20 in the reduction).
SINCOS_MAX_ABS = 1647099.3291652855  # 2**19 * pi

_INV_PIO2 = 6.36619772367581382433e-01  # 2/pi
_ROUND = 6755399441055744.0  # 1.5 * 2**52: (t + _ROUND) - _ROUND rounds t to an integer
_PIO2_1 = 1.57079632673412561417e00  # first 33 bits of pi/2
_PIO2_2 = 6.07710050630396597660e-11  # second 33 bits of pi/2
_PIO2_3 = 2.02226624871116645580e-21  # third 33 bits of pi/2
_PIO2_3T = 8.47842766036889956997e-32  # pi/2 - (_PIO2_1 + _PIO2_2 + _PIO2_3)

_S1 = -1.66666666666666324348e-01
_S2 = 8.33333333332248946124e-03
_S3 = -1.98412698298579493134e-04
_S4 = 2.75573137070700676789e-06
_S5 = -2.50507602534068634195e-08
_S6 = 1.58969099521155010221e-10

_C1 = 4.16666666666666019037e-02
_C2 = -1.38888888888741095749e-03
_C3 = 2.48015872894767294178e-05
_C4 = -2.75573143513906633035e-07
_C5 = 2.08757232129817482790e-09
_C6 = -1.13596475577881948265e-11


@kernel(inline=True)
def sincos(x):
    r"""``(sin x, cos x)`` by Cody-Waite reduction and fdlibm's minimax kernels (module
    docstring); branch-free, for :math:`|x| \le` :data:`SINCOS_MAX_ABS`."""
    k = (x * _INV_PIO2 + _ROUND) - _ROUND
    # r = x - k pi/2 = y0 + y1 to ~150 bits: k times each 33-bit part is exact, the first
    # difference is exact (Sterbenz), the next two are error-free sums (TwoSum)
    t = x - k * _PIO2_1
    b = -k * _PIO2_2
    r2 = t + b
    bb = r2 - t
    e2 = (t - (r2 - bb)) + (b - bb)
    b = -k * _PIO2_3
    r3 = r2 + b
    bb = r3 - r2
    e3 = (r2 - (r3 - bb)) + (b - bb)
    tail = (e2 + e3) - k * _PIO2_3T
    y0 = r3 + tail
    y1 = (r3 - y0) + tail
    # __kernel_sin(y0, y1, 1)
    z = y0 * y0
    v = z * y0
    poly = _S2 + z * (_S3 + z * (_S4 + z * (_S5 + z * _S6)))
    s = y0 - ((z * (0.5 * y1 - v * poly) - y1) - v * _S1)
    # __kernel_cos(y0, y1)
    zz = z * z
    poly = z * (_C1 + z * (_C2 + z * _C3)) + zz * zz * (_C4 + z * (_C5 + z * _C6))
    hz = 0.5 * z
    one_minus = 1.0 - hz
    c = one_minus + (((1.0 - one_minus) - hz) + (z * poly - y0 * y1))
    # quadrant k mod 4, exact in floating point
    quadrant = k - 4.0 * ((k * 0.25 + _ROUND) - _ROUND)
    quadrant = quadrant + 4.0 if quadrant < 0.0 else quadrant
    swap = quadrant == 1.0 or quadrant == 3.0
    sin_value = c if swap else s
    cos_value = s if swap else c
    sin_value = -sin_value if quadrant >= 2.0 else sin_value
    cos_value = -cos_value if (quadrant == 1.0 or quadrant == 2.0) else cos_value
    return sin_value, cos_value
