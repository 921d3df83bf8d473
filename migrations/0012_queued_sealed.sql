-- A queued message of an authenticated type keeps the bytes it was sealed
-- with (DCCL bytes and trailer: key id, send time, counter, tag), so that
-- after a restart it goes out byte-identical instead of sealed again with
-- a new time and counter. A receiver that accepted the first copy (its ack
-- lost) then recognises the resend as one it has, acknowledges the frame
-- and does not deliver the message twice.
--
-- NULL: not authenticated, or queued before this migration (sealed again
-- at restore, as before).
ALTER TABLE queued_messages ADD COLUMN sealed BLOB;
