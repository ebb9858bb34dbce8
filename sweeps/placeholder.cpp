// (replaced by the sweep engine)
