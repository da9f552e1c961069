//! GPU timestamp timers: one named span per pass, read back after the frame as milliseconds.

use std::cell::RefCell;
use std::sync::Arc;

use ash::vk;

use super::Context;
use crate::error::{Result, VkContext};

pub struct GpuTimer {
    ctx: Arc<Context>,
    pool: vk::QueryPool,
    capacity: u32,
    period_ns: f64,
    /// (name, first query index) of the spans recorded this frame.
    spans: RefCell<Vec<(String, u32)>>,
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
        let pool = unsafe { ctx.device.create_query_pool(&info, None) }.vk("vkCreateQueryPool")?;
        ctx.set_name(pool, "pass timers");
        unsafe { ctx.device.reset_query_pool(pool, 0, capacity) };
        Ok(GpuTimer {
            ctx: ctx.clone(),
            pool,
            capacity,
            period_ns: ctx.info.limits.timestamp_period as f64,
            spans: RefCell::new(Vec::new()),
        })
    }

    /// Forgets last frame's spans and resets the queries (record before the first span).
    pub fn reset(&self, cmd: vk::CommandBuffer) {
        self.spans.borrow_mut().clear();
        unsafe { self.ctx.device.cmd_reset_query_pool(cmd, self.pool, 0, self.capacity) };
    }

    /// Runs `record` between two timestamps named `name`.
    pub fn span<R>(&self, cmd: vk::CommandBuffer, name: &str, record: impl FnOnce() -> R) -> R {
        let index = self.spans.borrow().len() as u32 * 2;
        assert!(index + 1 < self.capacity, "more timer spans than the pool holds");
        self.spans.borrow_mut().push((name.to_string(), index));
        let d = &self.ctx.device;
        unsafe { d.cmd_write_timestamp2(cmd, vk::PipelineStageFlags2::ALL_COMMANDS, self.pool, index) };
        let r = record();
        unsafe { d.cmd_write_timestamp2(cmd, vk::PipelineStageFlags2::ALL_COMMANDS, self.pool, index + 1) };
        r
    }

    /// Reads the spans of the last submitted frame (call after it finished).
    pub fn read(&self) -> Result<Vec<Timing>> {
        let spans = self.spans.borrow();
        let n = spans.len() as u32 * 2;
        if n == 0 {
            return Ok(Vec::new());
        }
        let mut data = vec![0u64; n as usize];
        unsafe {
            self.ctx.device.get_query_pool_results(
                self.pool,
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
        unsafe { self.ctx.device.destroy_query_pool(self.pool, None) };
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
