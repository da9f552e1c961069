//! GPU timestamp timers: one named span per pass, read back after the frame as milliseconds;
//! a query pool per frame in flight.

use std::cell::RefCell;
use std::sync::Arc;

use ash::vk;

use super::{Context, FrameSlot, FRAMES_IN_FLIGHT};
use crate::error::{Result, VkContext};

pub struct GpuTimer {
    ctx: Arc<Context>,
    /// One query pool per frame in flight, used in turn: a frame's timestamps are read once
    /// its fence has passed, while the next frame writes the other pool.
    pools: [vk::QueryPool; FRAMES_IN_FLIGHT],
    /// The pool the last (or current) frame records into.
    current: FrameSlot,
    capacity: u32,
    period_ns: f64,
    /// Per pool, (name, first query index) of the spans its frame recorded.
    spans: [RefCell<Vec<(String, u32)>>; FRAMES_IN_FLIGHT],
}

/// One timed span: a pass name and its GPU time in milliseconds.
#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
pub struct Timing {
    pub pass: String,
    pub ms: f64,
}

impl GpuTimer {
    pub fn new(ctx: &Arc<Context>, max_spans: u32) -> Result<Self> {
        let capacity = max_spans * 2;
        let info = vk::QueryPoolCreateInfo::default().query_type(vk::QueryType::TIMESTAMP).query_count(capacity);
        let mut pools = [vk::QueryPool::null(); FRAMES_IN_FLIGHT];
        for (i, pool) in pools.iter_mut().enumerate() {
            *pool = match unsafe { ctx.device.create_query_pool(&info, None) }.vk("vkCreateQueryPool") {
                Ok(p) => p,
                Err(e) => {
                    for p in &pools[..i] {
                        unsafe { ctx.device.destroy_query_pool(*p, None) };
                    }
                    return Err(e);
                }
            };
            ctx.set_name(*pool, &format!("pass timers {i}"));
            unsafe { ctx.device.reset_query_pool(*pool, 0, capacity) };
        }
        Ok(GpuTimer {
            ctx: ctx.clone(),
            pools,
            current: FrameSlot::default(),
            capacity,
            period_ns: ctx.info.limits.timestamp_period as f64,
            spans: Default::default(),
        })
    }

    /// Starts a frame's timing in the next pool: forgets that pool's spans and resets its
    /// queries (record before the first span).
    pub fn reset(&self, cmd: vk::CommandBuffer) {
        let i = self.current.advance();
        self.spans[i].borrow_mut().clear();
        unsafe { self.ctx.device.cmd_reset_query_pool(cmd, self.pools[i], 0, self.capacity) };
    }

    /// Runs `record` between two timestamps named `name`.
    pub fn span<R>(&self, cmd: vk::CommandBuffer, name: &str, record: impl FnOnce() -> R) -> R {
        let i = self.current.last();
        let index = self.spans[i].borrow().len() as u32 * 2;
        assert!(index + 1 < self.capacity, "more timer spans than the pool holds");
        self.spans[i].borrow_mut().push((name.to_string(), index));
        let d = &self.ctx.device;
        unsafe { d.cmd_write_timestamp2(cmd, vk::PipelineStageFlags2::ALL_COMMANDS, self.pools[i], index) };
        let r = record();
        unsafe { d.cmd_write_timestamp2(cmd, vk::PipelineStageFlags2::ALL_COMMANDS, self.pools[i], index + 1) };
        r
    }

    /// Reads the spans of the last submitted frame (call after it finished).
    pub fn read(&self) -> Result<Vec<Timing>> {
        self.read_pool(self.current.last())
    }

    /// Reads the spans of the oldest frame still on record, the one `FRAMES_IN_FLIGHT - 1`
    /// frames before the last: with that many frames in flight, the one whose fence the next
    /// frame waits for (empty until one is recorded).
    pub fn read_settled(&self) -> Result<Vec<Timing>> {
        self.read_pool(self.current.settled())
    }

    fn read_pool(&self, i: usize) -> Result<Vec<Timing>> {
        let spans = self.spans[i].borrow();
        let n = spans.len() as u32 * 2;
        if n == 0 {
            return Ok(Vec::new());
        }
        let mut data = vec![0u64; n as usize];
        unsafe {
            self.ctx.device.get_query_pool_results(
                self.pools[i],
                0,
                &mut data,
                vk::QueryResultFlags::TYPE_64 | vk::QueryResultFlags::WAIT,
            )
        }
        .vk("vkGetQueryPoolResults")?;
        Ok(spans
            .iter()
            .map(|(name, i)| {
                let ticks = data[*i as usize + 1].saturating_sub(data[*i as usize]);
                Timing { pass: name.clone(), ms: ticks as f64 * self.period_ns / 1e6 }
            })
            .collect())
    }
}

impl Drop for GpuTimer {
    fn drop(&mut self) {
        for p in self.pools {
            unsafe { self.ctx.device.destroy_query_pool(p, None) };
        }
    }
}

/// Per-pass median over several frames' timings (passes matched by name, in first-frame order).
pub fn median(frames: &[Vec<Timing>]) -> Vec<Timing> {
    let Some(first) = frames.first() else { return Vec::new() };
    first
        .iter()
        .map(|t| {
            let mut ms: Vec<f64> =
                frames.iter().filter_map(|f| f.iter().find(|u| u.pass == t.pass)).map(|u| u.ms).collect();
            ms.sort_by(f64::total_cmp);
            Timing { pass: t.pass.clone(), ms: ms[ms.len() / 2] }
        })
        .collect()
}
