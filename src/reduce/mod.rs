//! Modal reduction: normal modes, Craig–Bampton, Craig–Chang, Dietz, reference conditions.
