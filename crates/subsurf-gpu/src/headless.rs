//! Quiet start-up on machines without a display server.
//!
//! Mesa's implicit Vulkan layer `VK_LAYER_MESA_device_select` orders GPUs by the display
//! they drive. When an application enables the Wayland surface extension (wgpu always does
//! where the driver offers it), the layer connects to a Wayland compositor while the adapters
//! are enumerated; without one, libwayland prints
//! `error: XDG_RUNTIME_DIR is invalid or not set in the environment.` on stderr for every
//! instance, although nothing failed. With no display server there is no display to select
//! by, so the layer has nothing to do: [`disable_display_layers_when_headless`] switches it
//! off through its documented `NODEVICE_SELECT=1` variable.

/// The environment variable that disables Mesa's device-select layer.
pub const NODEVICE_SELECT: &str = "NODEVICE_SELECT";

/// Whether the environment names a display server (`WAYLAND_DISPLAY` or `DISPLAY`).
pub fn has_display_server() -> bool {
    ["WAYLAND_DISPLAY", "DISPLAY"]
        .iter()
        .any(|v| std::env::var_os(v).is_some_and(|s| !s.is_empty()))
}

/// Sets `NODEVICE_SELECT=1` when no display server is named and the variable is not set
/// already; returns whether it did. Changing the environment is only sound while no other
/// thread reads it: call this at the start of `main`, before any thread is spawned (the
/// `subsurf` command line does). A user's own `NODEVICE_SELECT` is left as it is.
pub fn disable_display_layers_when_headless() -> bool {
    if has_display_server() || std::env::var_os(NODEVICE_SELECT).is_some() {
        return false;
    }
    std::env::set_var(NODEVICE_SELECT, "1");
    true
}
