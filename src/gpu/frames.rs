//! Frames in flight: per slot a command buffer and the fence its submission signals, used in turn,
//! so the host records frame N + 1 while the GPU still runs frame N. A frame waits only for the
//! fence of the frame that last used its slot, `depth` frames before. The viewer's swapchain
//! submits through one (adding its acquire and present semaphores); `vct render --in-flight K` runs
//! headless frames through one, to measure what the overlap buys on a device with no display.

use std::sync::Arc;

use ash::vk;

use super::{Context, FRAMES_IN_FLIGHT};
use crate::error::{Error, Result, VkContext};

pub struct FrameRing {
    ctx: Arc<Context>,
    pool: vk::CommandPool,
    cmds: Vec<vk::CommandBuffer>,
    fences: Vec<vk::Fence>,
    /// The slot the next frame takes.
    slot: usize,
}

impl FrameRing {
    /// A ring of `depth` slots (1: each frame waits for the one before; at most
    /// `FRAMES_IN_FLIGHT`, which the renderer's per-frame timers and read-backs are sized for).
    pub fn new(ctx: &Arc<Context>, depth: usize) -> Result<Self> {
        if !(1..=FRAMES_IN_FLIGHT).contains(&depth) {
            return Err(Error::param("in-flight", format!("{depth} is not in 1..={FRAMES_IN_FLIGHT}")));
        }
        let d = &ctx.device;
        let info = vk::CommandPoolCreateInfo::default()
            .queue_family_index(ctx.queue_family)
            .flags(vk::CommandPoolCreateFlags::RESET_COMMAND_BUFFER);
        let pool = unsafe { d.create_command_pool(&info, None) }.vk("vkCreateCommandPool")?;
        // Owned by `ring` (and freed by its Drop) before the next call can fail.
        let mut ring = FrameRing { ctx: ctx.clone(), pool, cmds: Vec::new(), fences: Vec::new(), slot: 0 };
        let alloc = vk::CommandBufferAllocateInfo::default().command_pool(pool).command_buffer_count(depth as u32);
        ring.cmds = unsafe { d.allocate_command_buffers(&alloc) }.vk("vkAllocateCommandBuffers")?;
        for _ in 0..depth {
            let signalled = vk::FenceCreateInfo::default().flags(vk::FenceCreateFlags::SIGNALED);
            ring.fences.push(unsafe { d.create_fence(&signalled, None) }.vk("vkCreateFence")?);
        }
        Ok(ring)
    }

    /// Frames that may be in flight at once.
    pub fn depth(&self) -> usize {
        self.cmds.len()
    }

    /// The slot the next frame takes (for per-slot objects the caller keeps beside the ring).
    pub fn slot(&self) -> usize {
        self.slot
    }

    /// Waits for the frame that last used the next slot.
    pub fn wait_slot(&self) -> Result<()> {
        self.wait(&self.fences[self.slot..self.slot + 1])
    }

    /// Waits until every frame in flight has finished.
    pub fn wait_idle(&self) -> Result<()> {
        self.wait(&self.fences)
    }

    fn wait(&self, fences: &[vk::Fence]) -> Result<()> {
        match unsafe { self.ctx.device.wait_for_fences(fences, true, super::context::GPU_TIMEOUT_S * 1_000_000_000) } {
            Ok(()) => Ok(()),
            Err(vk::Result::TIMEOUT) => Err(Error::Timeout("frame in flight".into(), super::context::GPU_TIMEOUT_S)),
            Err(result) => Err(Error::Vulkan { call: "vkWaitForFences", result }),
        }
    }

    /// Begins recording the next slot's commands (after [`Self::wait_slot`]).
    pub fn begin(&self) -> Result<vk::CommandBuffer> {
        let (d, cmd) = (&self.ctx.device, self.cmds[self.slot]);
        let info = vk::CommandBufferBeginInfo::default().flags(vk::CommandBufferUsageFlags::ONE_TIME_SUBMIT);
        unsafe {
            d.reset_fences(&self.fences[self.slot..self.slot + 1]).vk("vkResetFences")?;
            d.begin_command_buffer(cmd, &info).vk("vkBeginCommandBuffer")?;
        }
        Ok(cmd)
    }

    /// Ends the slot's commands and submits them: they wait for `wait` (before any command),
    /// and signal `signal` and the slot's fence. The next frame takes the next slot.
    pub fn submit(&mut self, wait: &[vk::Semaphore], signal: &[vk::Semaphore]) -> Result<()> {
        let (d, cmd, fence) = (&self.ctx.device, self.cmds[self.slot], self.fences[self.slot]);
        let stages = vec![vk::PipelineStageFlags::ALL_COMMANDS; wait.len()];
        let cmds = [cmd];
        let submit = [vk::SubmitInfo::default()
            .wait_semaphores(wait)
            .wait_dst_stage_mask(&stages)
            .command_buffers(&cmds)
            .signal_semaphores(signal)];
        unsafe {
            d.end_command_buffer(cmd).vk("vkEndCommandBuffer")?;
            d.queue_submit(self.ctx.queue, &submit, fence).vk("vkQueueSubmit")?;
        }
        self.slot = (self.slot + 1) % self.depth();
        Ok(())
    }

    /// One whole headless frame: waits for the slot, records `record` and submits.
    pub fn frame(&mut self, record: impl FnOnce(vk::CommandBuffer)) -> Result<()> {
        self.wait_slot()?;
        record(self.begin()?);
        self.submit(&[], &[])
    }
}

impl Drop for FrameRing {
    fn drop(&mut self) {
        unsafe {
            let d = &self.ctx.device;
            let _ = d.device_wait_idle();
            for f in self.fences.drain(..) {
                d.destroy_fence(f, None);
            }
            d.destroy_command_pool(self.pool, None);
        }
    }
}
