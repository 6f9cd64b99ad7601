//! Arithmetic written once for one lane or eight: [`Real`] is a number type that is either an
//! `f32` or eight of them side by side (`wide::f32x8`, one AVX register where the CPU has
//! AVX), and [`V3`] a 3-vector of it. Sampling warps, frames, ray spawning and the path
//! tracer's vertex arithmetic are written against [`Real`], so the path tracer's one-path code
//! and its eight-path packets run the same operations in the same order: every lane's answer
//! is bit for bit the one-lane answer.
//!
//! Branches become [`Real::select`]: both sides are computed and the mask picks one per lane
//! (for `f32` the mask is a `bool`).

use glam::Vec3;
use std::ops::{Add, BitAnd, BitOr, Div, Mul, Neg, Sub};
use wide::{CmpEq, CmpGe, CmpGt, CmpNe, f32x8};

/// Number of lanes of the wide type.
pub const LANES: usize = 8;

/// One `f32`, or [`LANES`] of them computed together.
pub trait Real:
    Copy
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
{
    /// Per-lane truth values.
    type Mask: Copy + BitAnd<Output = Self::Mask> + BitOr<Output = Self::Mask>;
    /// `v` in every lane.
    fn splat(v: f32) -> Self;
    /// Square root.
    fn sqrt(self) -> Self;
    /// Absolute value.
    fn abs(self) -> Self;
    /// The larger of `self` and `other` (for non-NaN values).
    fn max(self, other: Self) -> Self;
    /// ±1 with the sign bit of `self` (so −0 gives −1).
    fn sign_one(self) -> Self;
    /// `self > other`.
    fn gt(self, other: Self) -> Self::Mask;
    /// `self >= other`.
    fn ge(self, other: Self) -> Self::Mask;
    /// `self == other`.
    fn eq(self, other: Self) -> Self::Mask;
    /// `self != other`.
    fn ne(self, other: Self) -> Self::Mask;
    /// Per lane `a` where `mask` holds, `b` elsewhere.
    fn select(mask: Self::Mask, a: Self, b: Self) -> Self;
    /// [`Real::select`] of values computed on demand: one `f32` computes only the side it
    /// takes; eight lanes compute both.
    fn select_with(mask: Self::Mask, a: impl FnOnce() -> Self, b: impl FnOnce() -> Self) -> Self;
}

impl Real for f32 {
    type Mask = bool;
    #[inline(always)]
    fn splat(v: f32) -> f32 {
        v
    }
    #[inline(always)]
    fn sqrt(self) -> f32 {
        f32::sqrt(self)
    }
    #[inline(always)]
    fn abs(self) -> f32 {
        f32::abs(self)
    }
    #[inline(always)]
    fn max(self, other: f32) -> f32 {
        f32::max(self, other)
    }
    #[inline(always)]
    fn sign_one(self) -> f32 {
        1.0f32.copysign(self)
    }
    #[inline(always)]
    fn gt(self, other: f32) -> bool {
        self > other
    }
    #[inline(always)]
    fn ge(self, other: f32) -> bool {
        self >= other
    }
    #[inline(always)]
    fn eq(self, other: f32) -> bool {
        self == other
    }
    #[inline(always)]
    fn ne(self, other: f32) -> bool {
        self != other
    }
    #[inline(always)]
    fn select(mask: bool, a: f32, b: f32) -> f32 {
        if mask { a } else { b }
    }
    #[inline(always)]
    fn select_with(mask: bool, a: impl FnOnce() -> f32, b: impl FnOnce() -> f32) -> f32 {
        if mask { a() } else { b() }
    }
}

impl Real for f32x8 {
    type Mask = f32x8;
    #[inline(always)]
    fn splat(v: f32) -> f32x8 {
        f32x8::splat(v)
    }
    #[inline(always)]
    fn sqrt(self) -> f32x8 {
        f32x8::sqrt(self)
    }
    #[inline(always)]
    fn abs(self) -> f32x8 {
        f32x8::abs(self)
    }
    #[inline(always)]
    fn max(self, other: f32x8) -> f32x8 {
        self.fast_max(other)
    }
    #[inline(always)]
    fn sign_one(self) -> f32x8 {
        (self & f32x8::splat(-0.0)) | f32x8::ONE
    }
    #[inline(always)]
    fn gt(self, other: f32x8) -> f32x8 {
        self.cmp_gt(other)
    }
    #[inline(always)]
    fn ge(self, other: f32x8) -> f32x8 {
        self.cmp_ge(other)
    }
    #[inline(always)]
    fn eq(self, other: f32x8) -> f32x8 {
        self.cmp_eq(other)
    }
    #[inline(always)]
    fn ne(self, other: f32x8) -> f32x8 {
        self.cmp_ne(other)
    }
    #[inline(always)]
    fn select(mask: f32x8, a: f32x8, b: f32x8) -> f32x8 {
        mask.blend(a, b)
    }
    #[inline(always)]
    fn select_with(mask: f32x8, a: impl FnOnce() -> f32x8, b: impl FnOnce() -> f32x8) -> f32x8 {
        mask.blend(a(), b())
    }
}

/// A 3-vector (a point, a direction or an RGB colour) of [`Real`]s.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct V3<R> {
    /// First component.
    pub x: R,
    /// Second component.
    pub y: R,
    /// Third component.
    pub z: R,
}

/// Eight 3-vectors, one per lane.
pub type Vec3x8 = V3<f32x8>;

impl<R: Real> V3<R> {
    /// A vector from its components.
    #[inline(always)]
    pub fn new(x: R, y: R, z: R) -> Self {
        V3 { x, y, z }
    }

    /// Dot product `(x·x') + (y·y') + (z·z')`, summed in that order (as glam's `Vec3::dot`).
    #[inline(always)]
    pub fn dot(self, o: Self) -> R {
        (self.x * o.x) + (self.y * o.y) + (self.z * o.z)
    }

    /// Every component times `s`.
    #[inline(always)]
    pub fn scale(self, s: R) -> Self {
        V3::new(self.x * s, self.y * s, self.z * s)
    }

    /// Per lane `a` where `mask` holds, `b` elsewhere.
    #[inline(always)]
    pub fn select(mask: R::Mask, a: Self, b: Self) -> Self {
        V3::new(
            R::select(mask, a.x, b.x),
            R::select(mask, a.y, b.y),
            R::select(mask, a.z, b.z),
        )
    }
}

impl<R: Real> Add for V3<R> {
    type Output = Self;
    #[inline(always)]
    fn add(self, o: Self) -> Self {
        V3::new(self.x + o.x, self.y + o.y, self.z + o.z)
    }
}

impl<R: Real> Sub for V3<R> {
    type Output = Self;
    #[inline(always)]
    fn sub(self, o: Self) -> Self {
        V3::new(self.x - o.x, self.y - o.y, self.z - o.z)
    }
}

impl<R: Real> Mul for V3<R> {
    type Output = Self;
    /// Component-wise product.
    #[inline(always)]
    fn mul(self, o: Self) -> Self {
        V3::new(self.x * o.x, self.y * o.y, self.z * o.z)
    }
}

impl<R: Real> Neg for V3<R> {
    type Output = Self;
    #[inline(always)]
    fn neg(self) -> Self {
        V3::new(-self.x, -self.y, -self.z)
    }
}

impl From<Vec3> for V3<f32> {
    #[inline(always)]
    fn from(v: Vec3) -> Self {
        V3::new(v.x, v.y, v.z)
    }
}

impl From<V3<f32>> for Vec3 {
    #[inline(always)]
    fn from(v: V3<f32>) -> Self {
        Vec3::new(v.x, v.y, v.z)
    }
}

impl Vec3x8 {
    /// Lanes of a component array (`components[axis][lane]`) as a vector.
    #[inline(always)]
    pub fn load(components: &[[f32; LANES]; 3]) -> Self {
        V3::new(
            f32x8::new(components[0]),
            f32x8::new(components[1]),
            f32x8::new(components[2]),
        )
    }

    /// The vector as a component array (`[axis][lane]`).
    #[inline(always)]
    pub fn store(self) -> [[f32; LANES]; 3] {
        [self.x.to_array(), self.y.to_array(), self.z.to_array()]
    }

    /// The vectors `v[0..8]` as lanes.
    pub fn from_lanes(v: &[Vec3; LANES]) -> Self {
        V3::new(
            f32x8::new(v.map(|p| p.x)),
            f32x8::new(v.map(|p| p.y)),
            f32x8::new(v.map(|p| p.z)),
        )
    }

    /// The vector of lane `i`.
    pub fn lane(&self, i: usize) -> Vec3 {
        Vec3::new(
            self.x.as_array_ref()[i],
            self.y.as_array_ref()[i],
            self.z.as_array_ref()[i],
        )
    }
}
