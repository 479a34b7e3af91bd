pub mod exact;
pub mod hand;
