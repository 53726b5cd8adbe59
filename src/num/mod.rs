//! Numbers: the number types of the geometry pipeline and their precision contract
//! (`scalar`), vectors and matrices (`math`). Their exact wide integer arithmetic is the
//! kernel's (`kernel::wide`: it chooses forms by the core's capabilities).

pub(crate) mod math;
pub(crate) mod scalar;
