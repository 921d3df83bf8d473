-- Telemetry's reconstructed positions join the received sequence
-- (migration 0005), so that Subscribe's `after` replays them in their place
-- among received messages and `acommsctl sub --resume` resumes a track with
-- no gap.
--
-- seq: the position's number in the 'received' sequence (NULL for rows
-- stored before this migration, which are therefore not replayed; Track
-- still reads them). received: when it was reconstructed (seconds since the
-- Unix epoch), the receive_time a replayed Position carries.
ALTER TABLE telemetry_position ADD COLUMN seq INTEGER;
ALTER TABLE telemetry_position ADD COLUMN received REAL;

-- Replay reads "positions after N, in order": the index answers it alone.
CREATE UNIQUE INDEX telemetry_position_by_seq ON telemetry_position (seq) WHERE seq IS NOT NULL;
