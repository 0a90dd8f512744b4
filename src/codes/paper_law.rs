//! What every build with the paper's law offers beside its run: it is given η rather than a
//! COR, it refuses a clamp (its force never attracts), it runs batches and it has a card. Each
//! build says these in one line, [`paper_law_methods`], with its own reason, batches and card.

/// The [`CodeDriver`](crate::codes::CodeDriver) methods every build with the paper's law shares:
/// it takes η ([`takes_loss_coefficient`](crate::codes::CodeDriver::takes_loss_coefficient)),
/// refuses `--clamp` for the reason `$clamp_refusal`, runs the batches `$batch` (a
/// [`BatchRunner`](crate::codes::BatchRunner)) and has the card `$card` (a
/// [`CalibrationCard`](crate::codes::CalibrationCard)).
macro_rules! paper_law_methods {
    ($clamp_refusal:expr, $batch:expr, $card:expr) => {
        fn takes_loss_coefficient(&self) -> bool {
            true
        }

        fn clamp_refusal(&self) -> Option<&'static str> {
            Some($clamp_refusal)
        }

        fn batch(&self) -> Option<&dyn $crate::codes::BatchRunner> {
            Some(&$batch)
        }

        fn card(&self) -> Option<&dyn $crate::codes::CalibrationCard> {
            Some(&$card)
        }
    };
}

pub(crate) use paper_law_methods;
